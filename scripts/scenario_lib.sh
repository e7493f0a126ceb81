# Sourced by demo.sh, report.sh and screenshot.sh (with `root`, `py` and, for the A-Graph,
# ROS_HOME set): what they do alike with a scenario YAML.

# scenario_bag TOOL SCENARIO: sets `bag` (bags/<name>.bag), made when missing or older than
# its YAML.
scenario_bag() {
  bag="bags/$(basename "$2" .yaml).bag"
  if [ ! -f "${bag}" ] || [ "$2" -nt "${bag}" ]; then
    echo "$1: making ${bag} from $2"
    .ws/devel/lib/is_graphs/make_bag "$2" -o "${bag}" --quiet
  fi
}

# scenario_building SCENARIO: sets `building` (absolute) and `storey` ("" when none: the whole
# building) from it; `storey` is what the localizer is told: `localizer_storey` where given.
scenario_building() {
  read -r building storey < <("${py}" - "$1" <<'PYEOF'
import sys, yaml
s = yaml.safe_load(open(sys.argv[1]))
print(s["building"], str(s.get("localizer_storey", s.get("storey", ""))) or '""')
PYEOF
)
  [ "${storey}" = '""' ] && storey=""
  case "${building}" in /*) ;; *) building="${root}/${building}" ;; esac
}

# scenario_agraph: sets `agraph`, the A-Graph file of `building` (an IFC converted, cached).
scenario_agraph() {
  agraph="${building}"
  if [[ "${building,,}" == *.ifc ]]; then
    agraph="$("${py}" scripts/ifc_to_agraph.py "${building}" --cache-dir "${ROS_HOME}/is_graphs/cache" --quiet | tail -n 1)"
  fi
}
