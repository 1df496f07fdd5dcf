// Writing OFF/OBJ/PLY (ASCII and binary) and reading back bit-exactly; atomic replacement.
#include "pushpull/deform/mesh_io.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>

namespace pd = pushpull::deform;

namespace {

struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() / ("pushpull_mesh_io_" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
};

pd::Mesh awkward_mesh() {
  pd::Mesh mesh;
  mesh.V.resize(4, 3);
  mesh.V << 0.1, -2.5e-17, 3.0, 1.0 / 3.0, 2.0, -7.123456789012345, 1e10, 0.0, -0.0, 4.0, 5.0, 6.0;
  mesh.F.resize(2, 3);
  mesh.F << 0, 1, 2, 0, 2, 3;
  return mesh;
}

}  // namespace

TEST(MeshIoRoundTrip, EveryFormatReadsBackExactly) {
  TempDir dir;
  const pd::Mesh mesh = awkward_mesh();
  for (const char* name : {"m.off", "m.obj", "m.ply"}) {
    for (const pd::PlyEncoding encoding : {pd::PlyEncoding::binary_little_endian, pd::PlyEncoding::ascii}) {
      const std::filesystem::path path = dir.path / name;
      pd::write_mesh(path, mesh, {.ply_encoding = encoding});
      const pd::Mesh back = pd::read_mesh(path);
      EXPECT_EQ(back.V, mesh.V) << name;
      EXPECT_EQ(back.F, mesh.F) << name;
    }
  }
}

TEST(MeshIoRoundTrip, AtomicWriteReplacesAndLeavesNoTemporary) {
  TempDir dir;
  const std::filesystem::path path = dir.path / "out.off";
  { std::ofstream(path) << "old"; }
  pd::write_mesh(path, awkward_mesh());
  EXPECT_EQ(pd::read_mesh(path).V.rows(), 4);
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path)) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST(MeshIoRoundTrip, WriteIntoMissingFolderFailsNamingTheFile) {
  try {
    pd::write_mesh("/nonexistent/folder/out.obj", awkward_mesh());
    FAIL() << "no exception";
  } catch (const pd::MeshIoError& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/folder/out.obj"), std::string::npos)
        << error.what();
  }
}

TEST(MeshIoRoundTrip, RefusesFaceIndexOutOfRange) {
  pd::Mesh mesh = awkward_mesh();
  mesh.F(1, 2) = 9;
  EXPECT_THROW(pd::format_off(mesh), pd::MeshIoError);
}
