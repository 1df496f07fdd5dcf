// app/render_session's PictureRenderer (one Vulkan renderer for many pictures of a model, as the replay
// report uses it) on lavapipe: a picture does not depend on the pictures drawn before it in the same renderer
// (colour map, legend, overlays, arrow, size and eye count all replaced), a picture is refused for inputs of
// another model, and prepare_render_inputs measures colours from the rest shape it is given.
#include "render_inputs.hpp"
#include "render_model.hpp"
#include "render_session.hpp"

#include "pushpull/assets/model.hpp"
#include "pushpull/deform/mesh.hpp"
#include "pushpull/deform/metrics.hpp"
#include "pushpull/renderer/image_io.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using pushpull::app::PictureRenderer;
using pushpull::app::prepare_render_inputs;
using pushpull::app::RenderCommandOptions;
using pushpull::app::RenderInputs;
using pushpull::app::RenderModel;
using pushpull::renderer::TextureRGBA8;

// A wavy sheet of n x n vertices over [0, 1]^2 (y up), two triangles per cell.
pushpull::deform::Mesh wavy_sheet(int n) {
  pushpull::deform::Mesh mesh;
  mesh.V.resize(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = double(i) / (n - 1), z = double(j) / (n - 1);
      mesh.V.row(j * n + i) << x, 0.05 * std::sin(6.0 * x) * std::cos(5.0 * z), z;
    }
  mesh.F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      mesh.F.row(f++) << a, c, b;
      mesh.F.row(f++) << b, c, d;
    }
  return mesh;
}

// The sheet pulled up by a bump around its centre.
Eigen::MatrixXd pulled(const pushpull::deform::Mesh& mesh) {
  Eigen::MatrixXd V = mesh.V;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const double r2 = std::pow(V(v, 0) - 0.5, 2) + std::pow(V(v, 2) - 0.5, 2);
    V(v, 1) += 0.2 * std::exp(-r2 / 0.02);
  }
  return V;
}

RenderCommandOptions picture(const std::string& color, int width, int height) {
  RenderCommandOptions o;
  o.color = color;
  o.size = {width, height};
  o.samples = 1;
  return o;
}

int largest_difference(const TextureRGBA8& a, const TextureRGBA8& b) {
  if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size()) return 256;
  int largest = 0;
  for (std::size_t k = 0; k < a.pixels.size(); ++k)
    largest = std::max(largest, std::abs(a.pixels[k] - b.pixels[k]));
  return largest;
}

class PictureRendererTest : public ::testing::Test {
 protected:
  void SetUp() override {
    sheet = wavy_sheet(24);
    model = std::make_shared<const RenderModel>(
        pushpull::app::build_render_model(pushpull::assets::model_from_mesh(sheet, "sheet")));
    V = pulled(sheet);
  }
  pushpull::deform::Mesh sheet;
  std::shared_ptr<const RenderModel> model;
  Eigen::MatrixXd V;
};

TEST_F(PictureRendererTest, APictureDoesNotDependOnThePicturesBeforeIt) {
  // The material picture of the pulled sheet from a fresh renderer.
  const RenderCommandOptions plain = picture("material", 96, 64);
  const RenderInputs plain_inputs = prepare_render_inputs(model, sheet, V, true, plain, 1.0);
  TextureRGBA8 fresh;
  {
    PictureRenderer renderer(model, 1, false);
    fresh = renderer.render(plain_inputs, plain);
  }
  // The same after a stereo displacement picture with a legend, overlays and an arrow at another size, and a
  // curvature-sign picture of the rest shape.
  PictureRenderer renderer(model, 1, false);
  RenderCommandOptions busy = picture("displacement", 80, 80);
  busy.ipd = 0.05;
  busy.arrow = {0.5, 0.0, 0.5, 0.5, 0.2, 0.5};
  busy.handle_at = {0.5, 0.0, 0.5};
  busy.handle_radius = 0.2;
  const TextureRGBA8 stereo = renderer.render(prepare_render_inputs(model, sheet, V, true, busy, 1.0), busy);
  EXPECT_EQ(stereo.width, 160u);  // two eyes side by side
  const RenderCommandOptions curvature = picture("curvature-sign", 64, 48);
  (void)renderer.render(prepare_render_inputs(model, sheet, sheet.V, false, curvature, 1.0), curvature);
  const TextureRGBA8 reused = renderer.render(plain_inputs, plain);
  EXPECT_EQ(largest_difference(fresh, reused), 0);
  // And the picture differs from the stereo one's left eye: the test can tell pictures apart.
  EXPECT_NE(largest_difference(fresh, stereo), 0);
  EXPECT_EQ(renderer.close(), 0u);
  EXPECT_THROW((void)renderer.render(plain_inputs, plain), std::runtime_error);
}

// A model far from its file's origin (site coordinates) is drawn as it is at the origin: the picture of the
// sheet moved by a million metres, with an arrow, sections, and an eye and target given in its coordinates,
// matches the sheet's (floats in the model frame tore it apart: its cells 6 cm off, its normals striped).
TEST_F(PictureRendererTest, AModelFarFromTheOriginIsDrawnAsAtTheOrigin) {
  const Eigen::RowVector3d offset(1e6, -2e6, 3e5);
  pushpull::deform::Mesh far = sheet;
  far.V.rowwise() += offset;
  const Eigen::MatrixXd far_V = V.rowwise() + offset;
  const auto far_model = std::make_shared<const RenderModel>(
      pushpull::app::build_render_model(pushpull::assets::model_from_mesh(far, "far sheet")));
  auto options = [](const Eigen::RowVector3d& shift) {
    RenderCommandOptions o = picture("displacement", 96, 64);
    o.arrow = {0.5 + shift.x(), shift.y(),       0.5 + shift.z(),
               0.5 + shift.x(), 0.2 + shift.y(), 0.5 + shift.z()};
    o.sections = 3;
    o.eye = {1.6 + shift.x(), 1.2 + shift.y(), 1.9 + shift.z()};
    o.target = {0.5 + shift.x(), 0.05 + shift.y(), 0.5 + shift.z()};
    return o;
  };
  const RenderCommandOptions here = options(Eigen::RowVector3d::Zero()), there = options(offset);
  PictureRenderer near_renderer(model, 1, false), far_renderer(far_model, 1, false);
  const TextureRGBA8 near_picture =
      near_renderer.render(prepare_render_inputs(model, sheet, V, true, here, 1.0), here);
  const TextureRGBA8 far_picture =
      far_renderer.render(prepare_render_inputs(far_model, far, far_V, true, there, 1.0), there);
  int differing = 0;  // pixels off by more than rounding
  for (std::size_t k = 0; k + 3 < near_picture.pixels.size(); k += 4)
    for (int c = 0; c < 3; ++c)
      if (std::abs(near_picture.pixels[k + c] - far_picture.pixels[k + c]) > 8) {
        ++differing;
        break;
      }
  EXPECT_LE(differing, 10) << "of " << near_picture.pixels.size() / 4 << " pixels";
}

// The reversal picture marks exactly the vertices deform's metrics count as sign reversals (the paper's sign
// flips), each in the colour of its new sign, and nothing else.
TEST_F(PictureRendererTest, TheReversalPictureMarksTheReversalsTheMetricsCount) {
  const RenderCommandOptions o = picture("curvature-reversal", 64, 64);
  const RenderInputs inputs = prepare_render_inputs(model, sheet, V, true, o, 1.0);
  ASSERT_EQ(inputs.scalars.size(),
            std::size_t(sheet.V.rows()));  // a plain mesh: render vertex = deform vertex
  const pushpull::deform::DeformationMetrics metrics =
      pushpull::deform::evaluate_deformation(sheet, V, Eigen::Vector3d::UnitY(), {});
  const pushpull::deform::GaussianCurvature after = pushpull::deform::gaussian_curvature(V, sheet.F);
  const std::vector<std::int8_t> signs_after =
      pushpull::deform::curvature_signs(after, metrics.curvature_threshold);
  std::size_t marked = 0;
  for (std::size_t v = 0; v < inputs.scalars.size(); ++v)
    if (inputs.scalars[v] != 0.0f) {
      ++marked;
      EXPECT_EQ(inputs.scalars[v], float(signs_after[v])) << "vertex " << v;
    }
  EXPECT_GT(metrics.sign_reversals, 0u);  // the bump reverses some of the wavy sheet's signs
  EXPECT_EQ(marked, metrics.sign_reversals);
  // Drawn: the legend's three swatches and the sheet's reversed patches, in a picture of its own.
  PictureRenderer renderer(model, 1, false);
  const TextureRGBA8 image = renderer.render(inputs, o);
  EXPECT_EQ(image.width, 64u);
  // The rest shape against itself reverses nothing.
  const RenderInputs none = prepare_render_inputs(model, sheet, sheet.V, false, o, 1.0);
  EXPECT_TRUE(std::all_of(none.scalars.begin(), none.scalars.end(), [](float x) { return x == 0.0f; }));
}

TEST_F(PictureRendererTest, InputsOfAnotherModelAreRefused) {
  PictureRenderer renderer(model, 1, false);
  const auto other = std::make_shared<const RenderModel>(*model);
  const RenderCommandOptions o = picture("material", 32, 32);
  EXPECT_THROW((void)renderer.render(prepare_render_inputs(other, sheet, V, true, o, 1.0), o),
               std::runtime_error);
}

TEST_F(PictureRendererTest, ColoursAreMeasuredFromTheRestShapeGiven) {
  const RenderCommandOptions o = picture("displacement", 32, 32);
  // From the original sheet: the bump's height; from the pulled shape itself: nothing moved.
  const RenderInputs from_original = prepare_render_inputs(model, sheet, V, true, o, 1.0);
  EXPECT_NEAR(from_original.scalar_max, 0.2, 0.01);
  const pushpull::deform::Mesh pulled_shape{V, sheet.F};
  const RenderInputs from_pulled = prepare_render_inputs(model, pulled_shape, V, true, o, 1.0);
  EXPECT_EQ(from_pulled.scalar_max, 0.0);
  // Unmoved positions keep the file normals; moved ones turn with the surface.
  const RenderInputs rest = prepare_render_inputs(model, sheet, sheet.V, false, o, 1.0);
  EXPECT_EQ(rest.normals, model->file_normals);
  EXPECT_NE(from_original.normals, model->file_normals);
}

TEST(WritePicture, WritesAWholePngOrNothingAndNamesTheFile) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(PUSHPULL_BINARY_DIR) / "write-picture-test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  TextureRGBA8 image;
  image.width = 3;
  image.height = 2;
  image.pixels = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 255, 50, 60, 70, 255, 1, 2, 3, 4};
  const fs::path file = dir / "picture.png";
  pushpull::app::write_picture(file, image);
  const TextureRGBA8 back = pushpull::renderer::read_png(file);
  EXPECT_EQ(back.width, 3u);
  EXPECT_EQ(back.pixels, image.pixels);
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1);  // no temporary left beside it
  // A folder that does not exist: the error names the file.
  try {
    pushpull::app::write_picture(dir / "missing" / "picture.png", image);
    ADD_FAILURE() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("missing/picture.png"), std::string::npos) << e.what();
  }
  // An inconsistent image: refused, and the picture already there is kept whole.
  TextureRGBA8 broken = image;
  broken.pixels.pop_back();
  EXPECT_THROW(pushpull::app::write_picture(file, broken), std::runtime_error);
  EXPECT_EQ(pushpull::renderer::read_png(file).pixels, image.pixels);
}

}  // namespace
