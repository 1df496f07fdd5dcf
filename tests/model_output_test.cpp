// app/model_output: a deformed model written where the user asked, as the review and replay write it (the
// model loaded by assets, welded) and as deform does (read as it is).
#include "model_output.hpp"

#include "pushpull/assets/model.hpp"
#include "pushpull/deform/mesh_io.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
namespace pd = pushpull::deform;

namespace {

fs::path fresh_dir() {
  const fs::path dir =
      fs::temp_directory_path() / ("pushpull_model_output_" + std::to_string(::getpid()) + "_" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

// An OBJ split at a seam (its vertices 2 and 5, 3 and 6 the same points: an exporter's UV seam) and with a
// vertex no face uses: assets welds the seam, the solver moves the welded vertices, and the written OBJ is
// the source with each of its vertices at its weld's new position, the unused one as written, the faces and
// texture coordinates as they were.
TEST(ModelOutput, AWeldedObjIsWrittenBackAsItsOwnFile) {
  const fs::path dir = fresh_dir();
  const fs::path source = dir / "seam.obj";
  const std::string faces = "vt 0 0\nvt 1 1\nf 1/1 2/2 3/1 4/2\nf 5/1 7/1 8/2 6/2\n";
  std::ofstream(source)
      << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1.000000001 0 0\nv 1 1 0\nv 2 0 0\nv 2 1 0\n"
         "v 9.5 9.5 9.5\n"
      << faces;
  const pushpull::assets::Model model = pushpull::assets::load_model(source);
  ASSERT_EQ(model.deform_mesh.V.rows(), 6);  // the seam welded, the unused vertex gone
  Eigen::MatrixXd V = model.deform_mesh.V;
  V.col(2).array() += 0.25;
  const std::vector<std::string> warnings =
      pushpull::app::write_deformed_model(dir / "out.obj", source, model.deform_mesh, &model, V);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  const std::string written = text_of(dir / "out.obj");
  EXPECT_NE(written.find("\nv 9.5 9.5 9.5\n" + faces), std::string::npos) << written;
  const pd::Mesh back = pd::read_mesh(dir / "out.obj");
  ASSERT_EQ(back.V.rows(), 9);
  const pd::Mesh before = pd::read_mesh(source);
  for (Eigen::Index v = 0; v < 8; ++v) {
    EXPECT_EQ(back.V(v, 2), 0.25) << v;
    EXPECT_EQ(back.V.row(v).head<2>(), before.V.row(v).head<2>()) << v;
  }
  EXPECT_EQ(back.V.row(8), before.V.row(8));
  // As a .ply, another format: the file's own nine vertices in its numbering (the unused one too) and its
  // triangles, no note.
  EXPECT_TRUE(
      pushpull::app::write_deformed_model(dir / "out.ply", source, model.deform_mesh, &model, V).empty());
  const pd::Mesh ply = pd::read_mesh(dir / "out.ply");
  EXPECT_EQ(ply.F.rows(), 4);
  EXPECT_EQ(ply.V, back.V);
  // The source changed since it was read (its faces), or gone: the welded surface, and a warning that says
  // why.
  std::ofstream(source, std::ios::trunc)
      << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1.000000001 0 0\nv 1 1 0\nv 2 0 0\nv 2 1 0\n"
         "v 9.5 9.5 9.5\nf 1 2 3\nf 1 3 4\nf 5 7 8\nf 5 8 9\n";
  const std::vector<std::string> changed =
      pushpull::app::write_deformed_model(dir / "changed.ply", source, model.deform_mesh, &model, V);
  ASSERT_EQ(changed.size(), 1u);
  EXPECT_NE(changed.front().find("written as the welded surface (6 vertices): " + source.string() +
                                 " changed since it was read"),
            std::string::npos)
      << changed.front();
  EXPECT_EQ(pd::read_mesh(dir / "changed.ply").V.rows(), 6);
  fs::remove(source);
  const std::vector<std::string> gone =
      pushpull::app::write_deformed_model(dir / "gone.ply", source, model.deform_mesh, &model, V);
  ASSERT_EQ(gone.size(), 1u);
  EXPECT_NE(gone.front().find("can no longer be read"), std::string::npos) << gone.front();
  EXPECT_EQ(pd::read_mesh(dir / "gone.ply").V.rows(), 6);
}

// A glTF written as a mesh file says what it leaves out; an unwritable path is an error naming it.
TEST(ModelOutput, AGltfAsAMeshFileIsSaidAndAnUnwritablePathNamed) {
  const fs::path dir = fresh_dir();
  const fs::path box = fs::path(PUSHPULL_SHARED_DATA) / "gltf" / "Box_Draco" / "Box_Draco.glb";
  const pushpull::assets::Model model = pushpull::assets::load_model(box);
  const std::vector<std::string> warnings = pushpull::app::write_deformed_model(
      dir / "box.off", box, model.deform_mesh, &model, model.deform_mesh.V);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("holds the welded surface only"), std::string::npos) << warnings[0];
  try {
    (void)pushpull::app::write_deformed_model(dir / "missing" / "box.off", box, model.deform_mesh, &model,
                                              model.deform_mesh.V);
    ADD_FAILURE() << "wrote into a missing folder";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "missing" / "box.off").string()), std::string::npos)
        << e.what();
  }
}
