// The real car (AsamVehicle): when the nose is pulled 100 mm over a 2 m region, the parts riding on the
// body (headlamp lenses, the front number plate) move with it and stay on it, the wheels inside the pulled
// arches stay where they are, and parts away from the region keep their exact values.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "pushpull/assets/model.hpp"
#include "pushpull/deform/attached_parts.hpp"
#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"
#include "pushpull/deform/surface_point.hpp"
#include "pushpull/deform/triangle_bvh.hpp"

namespace fs = std::filesystem;
namespace pd = pushpull::deform;

namespace {

const fs::path kCar = fs::path(PUSHPULL_SHARED_DATA) / "gltf" / "AsamVehicle" / "vehicle_example.gltf";

// Deform vertices of the primitives whose name starts with `prefix`.
std::vector<int> vertices_of(const pushpull::assets::Model& model, const std::string& prefix) {
  std::vector<int> out;
  for (const auto& p : model.primitives) {
    if (p.name.rfind(prefix, 0) != 0) continue;
    for (int d : p.deform_vertex)
      if (d >= 0) out.push_back(d);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

TEST(CarParts, LampsAndPlateFollowTheNoseWheelsStay) {
  if (!fs::exists(kCar)) GTEST_SKIP() << kCar << " is missing";
  const pushpull::assets::Model model = pushpull::assets::load_model(kCar);
  const auto car = std::make_shared<const pd::Mesh>(model.deform_mesh);
  const pd::SurfacePoint hit = pd::closest_surface_point(*car, Eigen::Vector3d(1.855, 0.694, 0.0));
  const pd::RegionOfInterest roi = pd::build_roi(*car, pd::surface_handle(*car, hit, 0.05), {}, 2.0);
  const pd::AttachedParts parts(*car, roi);
  pd::Deformer deformer(car, roi, pd::DeformOptions{});
  const Eigen::Vector3d d(0.1, 0.0, 0.0);
  Eigen::MatrixXd V = deformer.solve(d).V;
  const Eigen::MatrixXd solved = V;
  parts.apply(V);

  const std::vector<int> plate = vertices_of(model, "License_Plate_F");
  const std::vector<int> lens_left = vertices_of(model, "Light_Low_Beam_Lens_FL");
  const std::vector<int> tire = vertices_of(model, "Tire_FL");
  const std::vector<int> rear_plate = vertices_of(model, "License_Plate_R");
  ASSERT_FALSE(plate.empty());
  ASSERT_FALSE(lens_left.empty());
  ASSERT_FALSE(tire.empty());
  ASSERT_FALSE(rear_plate.empty());
  // Before the binding the plate stays behind (the pulled nose swallows it).
  for (int v : plate) ASSERT_EQ(solved.row(v), car->V.row(v));
  // After it, plate and lens move forward with the nose (most of the 100 mm) ...
  for (const auto* part : {&plate, &lens_left}) {
    for (int v : *part) EXPECT_GT(V(v, 0) - car->V(v, 0), 0.06) << "vertex " << v;
  }
  // ... and do not sink into the body: every vertex keeps at least its rest distance to the body surface
  // within 2 mm, measured against the deformed body.
  std::vector<int> body_faces;
  for (int f = 0; f < car->F.rows(); ++f)
    if (roi.contains(car->F(f, 0))) body_faces.push_back(f);
  const pd::TriangleBvh rest_body(car->V, car->F, body_faces), moved_body(V, car->F, body_faces);
  for (const auto* part : {&plate, &lens_left}) {
    for (int v : *part) {
      const auto before = rest_body.closest_point(car->V, car->V.row(v).transpose());
      const auto after = moved_body.closest_point(V, V.row(v).transpose());
      ASSERT_TRUE(before && after);
      EXPECT_GT(after->distance, before->distance - 2e-3) << "vertex " << v << " sank into the body";
    }
  }
  // The wheel inside the pulled arch is neither dragged nor bent.
  for (int v : tire) EXPECT_EQ(V.row(v), car->V.row(v)) << "tire vertex " << v;
  // Far from the region: exact values.
  for (int v : rear_plate) EXPECT_EQ(V.row(v), car->V.row(v));
}

}  // namespace
