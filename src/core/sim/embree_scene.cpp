#include "is_graphs/sim/embree_scene.h"

// Embree 3 (Debian 11/12, Ubuntu) or 4 (Debian 13): CMake defines IS_GRAPHS_EMBREE_MAJOR from
// the version it found. The two give the same hits: same watertight triangle test, same scene
// flags; Embree 4 dropped the stream API (rtcIntersect1M), so there the batch is cast ray by ray.
#if IS_GRAPHS_EMBREE_MAJOR == 4
#include <embree4/rtcore.h>
#else
#include <embree3/rtcore.h>
#endif

#include <cstring>
#include <limits>

namespace is_graphs {
namespace sim {

struct EmbreeScene::Impl {
  RTCDevice device{nullptr};
  RTCScene scene{nullptr};
  std::vector<Eigen::Vector3f> normals;  // per triangle
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

EmbreeScene::EmbreeScene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
EmbreeScene::~EmbreeScene() = default;

Result<std::unique_ptr<EmbreeScene>> EmbreeScene::Create(const SceneMesh& mesh) {
  using R = Result<std::unique_ptr<EmbreeScene>>;
  if (mesh.triangles.empty()) return R::Error("embree: the scene has no triangles");
  auto impl = std::make_unique<Impl>();
  // One build thread: the BVH (and thus tie-breaking between coincident triangles) is the same
  // on every run.
  impl->device = rtcNewDevice("threads=1");
  if (!impl->device) return R::Error("embree: rtcNewDevice failed");
  impl->scene = rtcNewScene(impl->device);
  rtcSetSceneBuildQuality(impl->scene, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(impl->scene, RTC_SCENE_FLAG_ROBUST);

  RTCGeometry geom = rtcNewGeometry(impl->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                            RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                            mesh.triangles.size()));
  if (!vb || !ib) {
    rtcReleaseGeometry(geom);
    return R::Error("embree: cannot allocate the geometry buffers");
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    std::memcpy(vb + 3 * i, mesh.vertices[i].data(), 3 * sizeof(float));
  }
  impl->normals.resize(mesh.triangles.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Eigen::Vector3i& t = mesh.triangles[i];
    for (int k = 0; k < 3; ++k) ib[3 * i + k] = static_cast<unsigned>(t[k]);
    const Eigen::Vector3f n = (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                                  .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const float len = n.norm();
    impl->normals[i] = len > 0.0f ? Eigen::Vector3f(n / len) : Eigen::Vector3f::UnitZ();
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(impl->scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(impl->scene);
  if (rtcGetDeviceError(impl->device) != RTC_ERROR_NONE) {
    return R::Error("embree: building the scene failed");
  }
  return R::Ok(std::unique_ptr<EmbreeScene>(new EmbreeScene(std::move(impl))));
}

void EmbreeScene::Intersect(const std::vector<Ray>& rays, std::vector<RayHit>* hits) const {
  constexpr std::size_t kBatch = 1024;
  hits->resize(rays.size());
  std::vector<RTCRayHit> batch(std::min(kBatch, rays.size()));
#if IS_GRAPHS_EMBREE_MAJOR == 4
  RTCIntersectArguments arguments;
  rtcInitIntersectArguments(&arguments);
  arguments.flags = RTC_RAY_QUERY_FLAG_COHERENT;
#else
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
#endif
  for (std::size_t begin = 0; begin < rays.size(); begin += kBatch) {
    const std::size_t n = std::min(kBatch, rays.size() - begin);
    for (std::size_t i = 0; i < n; ++i) {
      const Ray& r = rays[begin + i];
      RTCRayHit& rh = batch[i];
      rh.ray.org_x = r.origin.x();
      rh.ray.org_y = r.origin.y();
      rh.ray.org_z = r.origin.z();
      rh.ray.dir_x = r.direction.x();
      rh.ray.dir_y = r.direction.y();
      rh.ray.dir_z = r.direction.z();
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = r.t_max;
      rh.ray.time = 0.0f;
      rh.ray.mask = 0xFFFFFFFFu;
      rh.ray.id = 0;
      rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
#if IS_GRAPHS_EMBREE_MAJOR == 4
    for (std::size_t i = 0; i < n; ++i) rtcIntersect1(impl_->scene, &batch[i], &arguments);
#else
    rtcIntersect1M(impl_->scene, &context, batch.data(), static_cast<unsigned>(n),
                   sizeof(RTCRayHit));
#endif
    for (std::size_t i = 0; i < n; ++i) {
      RayHit& out = (*hits)[begin + i];
      if (batch[i].hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        out.distance = std::numeric_limits<float>::infinity();
        out.normal = Eigen::Vector3f::Zero();
        out.triangle = -1;
      } else {
        out.distance = batch[i].ray.tfar;
        out.triangle = static_cast<int>(batch[i].hit.primID);
        out.normal = impl_->normals[out.triangle];
      }
    }
  }
}

RayHit EmbreeScene::Intersect(const Ray& ray) const {
  std::vector<RayHit> hits;
  Intersect(std::vector<Ray>{ray}, &hits);
  return hits[0];
}

}  // namespace sim
}  // namespace is_graphs
