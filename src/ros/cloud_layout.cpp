#include "cloud_layout.h"

#include <initializer_list>
#include <map>
#include <set>
#include <utility>

namespace is_graphs {
namespace ros_conversions {
namespace {

using sensor_msgs::PointField;

const char* TypeName(std::uint8_t datatype) {
  switch (datatype) {
    case PointField::INT8:
      return "int8";
    case PointField::UINT8:
      return "uint8";
    case PointField::INT16:
      return "int16";
    case PointField::UINT16:
      return "uint16";
    case PointField::INT32:
      return "int32";
    case PointField::UINT32:
      return "uint32";
    case PointField::FLOAT32:
      return "float32";
    case PointField::FLOAT64:
      return "float64";
    default:
      return "unknown";
  }
}

// The time field each driver writes.
struct TimeField {
  const char* name;
  std::uint8_t datatype;
  TimeEncoding encoding;
  const char* what;
};

TimeField TimeFieldOf(CloudLayoutKind kind) {
  switch (kind) {
    case CloudLayoutKind::kVelodyne:
      return {"time", PointField::FLOAT32, TimeEncoding::kSecondsF32Relative,
              "float32, s after the stamp"};
    case CloudLayoutKind::kOuster:
      return {"t", PointField::UINT32, TimeEncoding::kNanosU32Relative,
              "uint32, ns after the stamp"};
    case CloudLayoutKind::kHesai:
    case CloudLayoutKind::kRobosense:
      return {"timestamp", PointField::FLOAT64, TimeEncoding::kSecondsF64Absolute,
              "float64, absolute s"};
    default:
      return {"", 0, TimeEncoding::kNone, ""};
  }
}

// The fields by name, in message order; a name given twice is listed in `duplicates`.
class FieldIndex {
 public:
  FieldIndex(const std::vector<PointField>& fields, std::uint32_t point_step) {
    for (const PointField& f : fields) {
      if (!by_name_.emplace(f.name, &f).second) duplicates_.insert(f.name);
      const bool inside = static_cast<std::uint64_t>(f.offset) + DatatypeSize(f.datatype) <=
                          static_cast<std::uint64_t>(point_step);
      if (!inside) outside_.insert(f.name);
      listing_ += (listing_.empty() ? "" : " ") + f.name + "(" + TypeName(f.datatype) + ")";
    }
    if (listing_.empty()) listing_ = "none";
  }
  // The field `name` when it is there once, inside the point, of one of `types`; else why not
  // in `why` (empty when absent).
  FieldSlot Find(const std::string& name, std::initializer_list<std::uint8_t> types,
                 std::string* why) const {
    FieldSlot slot;
    const auto it = by_name_.find(name);
    if (it == by_name_.end()) return slot;
    const PointField& f = *it->second;
    if (duplicates_.count(name)) {
      *why = "field '" + name + "' appears more than once";
    } else if (outside_.count(name) || DatatypeSize(f.datatype) == 0) {
      *why = "field '" + name + "' lies outside point_step";
    } else {
      bool typed = false;
      for (std::uint8_t t : types) typed = typed || f.datatype == t;
      if (!typed) {
        *why = "field '" + name + "' is " + TypeName(f.datatype);
      } else {
        slot.present = true;
        slot.name = name;
        slot.offset = f.offset;
        slot.datatype = f.datatype;
      }
    }
    return slot;
  }
  bool Has(const std::string& name) const { return by_name_.count(name) > 0; }
  const std::string& listing() const { return listing_; }

 private:
  std::map<std::string, const PointField*> by_name_;
  std::set<std::string> duplicates_, outside_;
  std::string listing_;
};

void Append(std::string* text, const std::string& more) {
  if (!more.empty()) *text += (text->empty() ? "" : "; ") + more;
}

// The time field of `kind` into `layout` (or a warning saying why there is none).
void SetTime(const FieldIndex& index, CloudLayoutKind kind, bool forced, CloudLayout* layout) {
  const TimeField expected = TimeFieldOf(kind);
  std::string why;
  layout->time = index.Find(expected.name, {expected.datatype}, &why);
  if (layout->time.present) {
    layout->time_encoding = expected.encoding;
    return;
  }
  if (why.empty()) why = "no field '" + std::string(expected.name) + "'";
  Append(&layout->warning, std::string(forced ? "cloud_layout " : "layout ") + ToString(kind) +
                               " expects '" + expected.name + "' (" + expected.what + "), but " +
                               why + ": no per-point time, no deskew");
}

}  // namespace

const char* ToString(CloudLayoutKind kind) {
  switch (kind) {
    case CloudLayoutKind::kAuto:
      return "auto";
    case CloudLayoutKind::kVelodyne:
      return "velodyne";
    case CloudLayoutKind::kOuster:
      return "ouster";
    case CloudLayoutKind::kHesai:
      return "hesai";
    case CloudLayoutKind::kRobosense:
      return "robosense";
    case CloudLayoutKind::kXyzi:
      return "xyzi";
  }
  return "?";
}

std::optional<CloudLayoutKind> ParseCloudLayoutKind(const std::string& name) {
  for (auto kind : {CloudLayoutKind::kAuto, CloudLayoutKind::kVelodyne, CloudLayoutKind::kOuster,
                    CloudLayoutKind::kHesai, CloudLayoutKind::kRobosense, CloudLayoutKind::kXyzi})
    if (name == ToString(kind)) return kind;
  return std::nullopt;
}

std::string CloudLayoutChoices() { return "auto, velodyne, ouster, hesai, robosense, xyzi"; }

std::uint32_t DatatypeSize(std::uint8_t datatype) {
  switch (datatype) {
    case PointField::INT8:
    case PointField::UINT8:
      return 1;
    case PointField::INT16:
    case PointField::UINT16:
      return 2;
    case PointField::INT32:
    case PointField::UINT32:
    case PointField::FLOAT32:
      return 4;
    case PointField::FLOAT64:
      return 8;
    default:
      return 0;
  }
}

std::string FieldsSignature(const std::vector<PointField>& fields, std::uint32_t point_step) {
  std::string s = std::to_string(point_step);
  for (const PointField& f : fields)
    s += "|" + f.name + ":" + std::to_string(f.offset) + ":" + std::to_string(f.datatype) + ":" +
         std::to_string(f.count);
  return s;
}

CloudLayout DetectCloudLayout(const std::vector<PointField>& fields, std::uint32_t point_step,
                              CloudLayoutKind forced) {
  const FieldIndex index(fields, point_step);
  CloudLayout layout;
  layout.fields = index.listing();
  std::string why;
  for (auto [slot, name] :
       {std::pair<FieldSlot*, const char*>{&layout.x, "x"}, {&layout.y, "y"}, {&layout.z, "z"}}) {
    why.clear();
    *slot = index.Find(name, {PointField::FLOAT32}, &why);
    if (!slot->present) {
      layout.error = (why.empty() ? "no field '" + std::string(name) + "'" : why) +
                     " (x, y, z must be float32; fields: " + layout.fields + ")";
      return layout;
    }
  }
  why.clear();
  layout.intensity =
      index.Find("intensity", {PointField::FLOAT32, PointField::UINT8, PointField::UINT16}, &why);
  if (!why.empty()) Append(&layout.warning, why + ": intensity left out");
  why.clear();
  layout.ring = index.Find("ring", {PointField::UINT16, PointField::UINT8}, &why);
  if (!why.empty()) Append(&layout.warning, why + ": ring left out");

  if (forced != CloudLayoutKind::kAuto) {
    layout.kind = forced;
    if (forced != CloudLayoutKind::kXyzi) SetTime(index, forced, true, &layout);
  } else if (index.Has("time")) {
    layout.kind = CloudLayoutKind::kVelodyne;
    SetTime(index, layout.kind, false, &layout);
  } else if (index.Has("t")) {
    layout.kind = CloudLayoutKind::kOuster;
    SetTime(index, layout.kind, false, &layout);
  } else if (index.Has("timestamp")) {
    // Hesai writes `timestamp` before `ring`, RoboSense after it; both mean the same.
    layout.kind = CloudLayoutKind::kHesai;
    why.clear();
    const FieldSlot t = index.Find("timestamp", {PointField::FLOAT64}, &why);
    if (t.present && layout.ring.present && layout.ring.offset < t.offset)
      layout.kind = CloudLayoutKind::kRobosense;
    SetTime(index, layout.kind, false, &layout);
  } else {
    layout.kind = CloudLayoutKind::kXyzi;
    Append(&layout.warning,
           "no per-point time field ('time' float32, 't' uint32 or 'timestamp' float64): no "
           "deskew");
  }
  if (!layout.warning.empty()) layout.warning += " (fields: " + layout.fields + ")";
  return layout;
}

}  // namespace ros_conversions
}  // namespace is_graphs
