// OFF/OBJ/PLY reading: valid files, polygons, and every refused input with a message naming the problem.
#include "pushpull/deform/mesh_io.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

namespace pd = pushpull::deform;

namespace {

const std::filesystem::path kMeshes = std::filesystem::path(PUSHPULL_SHARED_DATA) / "meshes";

// Runs `parse` and returns the MeshIoError message ("" if nothing was thrown).
template <typename Parse>
std::string error_of(Parse parse) {
  try {
    parse();
  } catch (const pd::MeshIoError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST(MeshIoRead, SharedOffMeshesLoadWithPlausibleCounts) {
  const pd::Mesh hemisphere = pd::read_mesh(kMeshes / "hemisphere.off");
  EXPECT_EQ(hemisphere.V.rows(), 1861);
  EXPECT_EQ(hemisphere.F.rows(), 3600);
  const pd::Mesh fandisk = pd::read_mesh(kMeshes / "fandisk.off");
  EXPECT_EQ(fandisk.V.rows(), 6475);
  EXPECT_EQ(fandisk.F.rows(), 12946);
  const pd::Mesh cactus = pd::read_mesh(kMeshes / "cactus" / "cactus.off");  // COFF header
  EXPECT_EQ(cactus.V.rows(), 620);
  EXPECT_EQ(cactus.F.rows(), 1236);
}

TEST(MeshIoRead, ChamferCubeQuadsAreFanTriangulated) {
  const pd::Mesh cube = pd::read_mesh(kMeshes / "chamfer-cube.off");
  EXPECT_EQ(cube.V.rows(), 24);
  // 26 faces: 8 triangles and 18 quads (2 triangles each).
  EXPECT_EQ(cube.F.rows(), 8 + 2 * 18);
  EXPECT_GE(cube.F.minCoeff(), 0);
  EXPECT_LT(cube.F.maxCoeff(), 24);
}

TEST(MeshIoRead, OffPolygonFanAndCountsOnHeaderLine) {
  const pd::Mesh mesh =
      pd::parse_off("OFF 5 1 0\n0 0 0\n1 0 0\n1 1 0\n0.5 1.5 0\n0 1 0\n5 0 1 2 3 4\n", "pentagon.off");
  ASSERT_EQ(mesh.F.rows(), 3);
  EXPECT_EQ(mesh.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(mesh.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(mesh.F.row(2), Eigen::RowVector3i(0, 3, 4));
}

TEST(MeshIoRead, OffRefusals) {
  // Small enough for the count check to pass, yet missing the third vertex.
  const std::string truncated =
      error_of([] { (void)pd::parse_off("OFF\n3 1 0\n0.00000000 0.00000000 0.00000000\n1 0 0\n", "t.off"); });
  EXPECT_NE(truncated.find("t.off:4: truncated: 2 of 3 vertices"), std::string::npos) << truncated;
  // Counts the bytes cannot hold even as two-byte records: refused at the counts line. Short records are read
  // and refused for what they are (a face "2 0 1" was refused as a corrupt count).
  const std::string counts = error_of([] { (void)pd::parse_off("OFF\n30 1 0\n0 0 0\n1 0 0\n", "c.off"); });
  EXPECT_NE(counts.find("c.off:2: header claims 30 vertices"), std::string::npos) << counts;
  const std::string cut = error_of([] { (void)pd::parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n", "cut.off"); });
  EXPECT_NE(cut.find("cut.off:4: truncated: 2 of 3 vertices read"), std::string::npos) << cut;
  const std::string two =
      error_of([] { (void)pd::parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "two.off"); });
  EXPECT_NE(two.find("two.off:6: face with 2 vertices"), std::string::npos) << two;
  const std::string flat =
      error_of([] { (void)pd::parse_off("OFF\n3 1 0\n0 0\n1 0\n0 1\n3 0 1 2\n", "xy.off"); });
  EXPECT_NE(flat.find("xy.off:3: vertex 0 has fewer than 3 coordinates"), std::string::npos) << flat;
  const std::string absurd = error_of([] { (void)pd::parse_off("OFF\n2000000000 1 0\n0 0 0\n", "big.off"); });
  EXPECT_NE(absurd.find("big.off:2"), std::string::npos) << absurd;
  EXPECT_NE(absurd.find("2000000000"), std::string::npos) << absurd;
  const std::string range =
      error_of([] { (void)pd::parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "r.off"); });
  EXPECT_NE(range.find("r.off:6"), std::string::npos) << range;
  EXPECT_NE(range.find("out of range"), std::string::npos) << range;
  const std::string nan =
      error_of([] { (void)pd::parse_off("OFF\n3 1 0\n0 nan 0\n1 0 0\n0 1 0\n3 0 1 2\n", "n.off"); });
  EXPECT_NE(nan.find("n.off:3"), std::string::npos) << nan;
  EXPECT_NE(nan.find("NaN"), std::string::npos) << nan;
  EXPECT_NE(error_of([] { (void)pd::parse_off("PLY\n", "x.off"); }).find("not an OFF file"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              (void)pd::parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1    \n", "d.off");
            }).find("at least 3"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              (void)pd::parse_off("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", "b.off");
            }).find("b.off:4"),
            std::string::npos);
}

// What a refused token is: a number beyond a double's range is said to be one (1e-400 was "not a number"),
// a control byte is quoted as \xNN (a NUL reached the terminal), a huge index names the vertices there are.
TEST(MeshIoRead, RefusedTokensAreNamedForWhatTheyAre) {
  const std::string under =
      error_of([] { (void)pd::parse_off("OFF\n3 1 0\n1e-400 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "u.off"); });
  EXPECT_NE(under.find("u.off:3: vertex 0: '1e-400' is out of a double's range (it underflows to 0)"),
            std::string::npos)
      << under;
  const std::string over =
      error_of([] { (void)pd::parse_obj("v 1e400 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "o.obj"); });
  EXPECT_NE(over.find("'1e400' is out of a double's range (it overflows)"), std::string::npos) << over;
  const std::string tiny = "0." + std::string(400, '0') + "1";  // underflows without an exponent
  const std::string small = error_of(
      [&] { (void)pd::parse_off("OFF\n3 1 0\n" + tiny + " 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "s.off"); });
  EXPECT_NE(small.find("is out of a double's range (it underflows to 0)"), std::string::npos) << small;
  const std::string nul = error_of(
      [] { (void)pd::parse_off(std::string("OFF\n3 1 0\n0 0 0\n1 x\0y 0\n0 1 0\n3 0 1 2\n", 38), "z.off"); });
  EXPECT_NE(nul.find("'x\\x00y' is not a number"), std::string::npos) << nul;
  EXPECT_EQ(nul.find('\0'), std::string::npos);
  const std::string huge =
      error_of([] { (void)pd::parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 4294967296\n", "h.off"); });
  EXPECT_NE(huge.find("vertex index 4294967296 out of range (the file has 3 vertices so far)"),
            std::string::npos)
      << huge;
}

TEST(MeshIoRead, ObjSlashesNegativeIndicesAndIgnoredRecords) {
  const std::string text =
      "# square\nmtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1.0\nvt 0 0\nvn 0 0 1\n"
      "g sq\nf 1/1/1 2/2/1 3//1 -1\n";
  const pd::Mesh mesh = pd::parse_obj(text, "square.obj");
  ASSERT_EQ(mesh.V.rows(), 4);
  ASSERT_EQ(mesh.F.rows(), 2);
  EXPECT_EQ(mesh.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(mesh.F.row(1), Eigen::RowVector3i(0, 2, 3));
  const std::string range = error_of([] { (void)pd::parse_obj("v 0 0 0\nv 1 0 0\nf 1 2 3\n", "r.obj"); });
  EXPECT_NE(range.find("r.obj:3"), std::string::npos) << range;
  EXPECT_NE(range.find("out of range"), std::string::npos) << range;
  EXPECT_NE(error_of([] { (void)pd::parse_obj("v 0 0 0\nf -2 1 1\n", "n.obj"); }).find("n.obj:2"),
            std::string::npos);
  EXPECT_NE(error_of([] { (void)pd::parse_obj("v 0 0 0\nf 0 1 1\n", "z.obj"); }).find("bad face vertex"),
            std::string::npos);
  const std::string continued =
      error_of([] { (void)pd::parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n 3\n", "c.obj"); });
  EXPECT_NE(continued.find("c.obj:4: a line continued with '\\' is not supported"), std::string::npos)
      << continued;
  // Glued to the last index or on a vertex line: the same.
  for (const char* text : {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\\\n 3\n", "v 0 0 0\nv 1 0 \\\n0\n"}) {
    const std::string glued = error_of([&] { (void)pd::parse_obj(text, "g.obj"); });
    EXPECT_NE(glued.find("a line continued with '\\' is not supported"), std::string::npos) << glued;
  }
}

TEST(MeshIoRead, PlyAsciiWithExtraPropertiesAndElements) {
  const std::string text =
      "ply\nformat ascii 1.0\ncomment test\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
      "0 0 0 255\n1 0 0 0\n1 1 0 0\n0 1 0 0\n4 0 1 2 3\n0 1\n";
  const pd::Mesh mesh = pd::parse_ply(text, "sq.ply");
  ASSERT_EQ(mesh.V.rows(), 4);
  ASSERT_EQ(mesh.F.rows(), 2);
  EXPECT_EQ(mesh.V(2, 1), 1.0);
  EXPECT_EQ(mesh.F.row(1), Eigen::RowVector3i(0, 2, 3));
}

TEST(MeshIoRead, PlyRefusals) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\n"
      "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string absurd = error_of([&] { (void)pd::parse_ply(header + "abc", "big.ply"); });
  EXPECT_NE(absurd.find("big.ply:3"), std::string::npos) << absurd;
  EXPECT_NE(absurd.find("1000000000"), std::string::npos) << absurd;
  const std::string truncated = error_of([] {
    (void)pd::parse_ply(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n",
        "t.ply");
  });
  EXPECT_NE(truncated.find("t.ply"), std::string::npos) << truncated;
  EXPECT_NE(truncated.find("truncated"), std::string::npos) << truncated;
  EXPECT_NE(error_of([] {
              (void)pd::parse_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "h.ply");
            }).find("end_header"),
            std::string::npos);
  EXPECT_NE(error_of([] { (void)pd::parse_ply("solid x\n", "m.ply"); }).find("not a PLY"), std::string::npos);
}

TEST(MeshIoRead, PlyBinaryBigEndianWithFloatCoordinates) {
  std::string text =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
      "float z\n"
      "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  auto put_float = [&](float value) {
    unsigned char bytes[4];
    std::memcpy(bytes, &value, 4);
    for (int i = 3; i >= 0; --i) text.push_back(static_cast<char>(bytes[i]));  // host is little-endian
  };
  for (const float value : {0.0f, 0.0f, 0.0f, 1.5f, 0.0f, 0.0f, 0.0f, -2.0f, 0.25f}) put_float(value);
  text.push_back(3);
  for (const char index : {0, 1, 2}) text.append({0, 0, 0, index});
  const pd::Mesh mesh = pd::parse_ply(text, "be.ply");
  ASSERT_EQ(mesh.V.rows(), 3);
  EXPECT_EQ(mesh.V(1, 0), 1.5);
  EXPECT_EQ(mesh.V(2, 1), -2.0);
  EXPECT_EQ(mesh.V(2, 2), 0.25);
  EXPECT_EQ(mesh.F.row(0), Eigen::RowVector3i(0, 1, 2));
  // Cut the last byte: truncated binary data.
  text.pop_back();
  EXPECT_NE(error_of([&] { (void)pd::parse_ply(text, "be.ply"); }).find("truncated"), std::string::npos);
}

TEST(MeshIoRead, UnknownExtensionAndMissingFileNameTheFile) {
  const std::string unknown = error_of([] { (void)pd::read_mesh("model.stl"); });
  EXPECT_NE(unknown.find("model.stl"), std::string::npos) << unknown;
  const std::string missing = error_of([] { (void)pd::read_mesh("/nonexistent/dir/m.off"); });
  EXPECT_NE(missing.find("/nonexistent/dir/m.off"), std::string::npos) << missing;
  EXPECT_NE(missing.find("cannot open"), std::string::npos) << missing;
}

// Every prefix of a valid file either parses or throws MeshIoError: no crash, no other exception, no
// over-read (run under the sanitizer tree too).
TEST(MeshIoRead, EveryTruncationFailsCleanly) {
  pd::Mesh mesh;
  mesh.V.resize(5, 3);
  mesh.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1;
  mesh.F.resize(4, 3);
  mesh.F << 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4;
  const std::string files[] = {pd::format_off(mesh), pd::format_obj(mesh),
                               pd::format_ply(mesh, pd::PlyEncoding::ascii),
                               pd::format_ply(mesh, pd::PlyEncoding::binary_little_endian)};
  for (int kind = 0; kind < 4; ++kind) {
    const std::string& full = files[kind];
    for (std::size_t length = 0; length <= full.size(); ++length) {
      const std::string_view prefix(full.data(), length);
      try {
        const pd::Mesh back = kind == 0   ? pd::parse_off(prefix, "p")
                              : kind == 1 ? pd::parse_obj(prefix, "p")
                                          : pd::parse_ply(prefix, "p");
        EXPECT_LE(back.F.rows(), 4);
      } catch (const pd::MeshIoError&) {
      }
    }
    EXPECT_EQ((kind == 0   ? pd::parse_off(full, "p")
               : kind == 1 ? pd::parse_obj(full, "p")
                           : pd::parse_ply(full, "p"))
                  .V,
              mesh.V);
  }
}

// A UTF-8 byte order mark at the start is not part of the first record: the OBJ's first vertex stays (it was
// dropped and every face index shifted), and the OFF and PLY headers read as without it.
TEST(MeshIoRead, AByteOrderMarkIsSkipped) {
  const std::string bom = "\xEF\xBB\xBF";
  const pd::Mesh obj =
      pd::parse_obj(bom + "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\nf 1 3 4\n", "bom.obj");
  ASSERT_EQ(obj.V.rows(), 5);
  EXPECT_EQ(obj.V.row(0), Eigen::RowVector3d(0, 0, 0));
  EXPECT_EQ(obj.F.row(1), Eigen::RowVector3i(0, 2, 3));
  const pd::Mesh off = pd::parse_off(bom + "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "bom.off");
  EXPECT_EQ(off.F.rows(), 1);
  const pd::Mesh ply =
      pd::parse_ply(bom +
                        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty "
                        "float y\nproperty float z\nelement face 1\nproperty list uchar int "
                        "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                    "bom.ply");
  EXPECT_EQ(ply.V(1, 0), 1.0);
  EXPECT_EQ(ply.F.rows(), 1);
}

// A header count smaller than the records that follow would drop faces unseen (holes, parts left behind):
// refused at the first record not declared. Trailing blank lines and comments stay fine.
TEST(MeshIoRead, DataAfterTheDeclaredRecordsIsRefused) {
  const std::string off = error_of(
      [] { (void)pd::parse_off("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n", "o.off"); });
  EXPECT_NE(off.find("o.off:8: more data after the 1 faces the header declares ('3')"), std::string::npos)
      << off;
  EXPECT_EQ(
      pd::parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n\n# end\n  \n", "c.off").F.rows(), 1);
  const std::string ply_header =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n";
  const std::string ply = error_of([&] { (void)pd::parse_ply(ply_header + "3 0 1 2\n3 1 3 2\n", "p.ply"); });
  EXPECT_NE(ply.find("p.ply:15: more data after the elements the header declares ('3')"), std::string::npos)
      << ply;
  EXPECT_EQ(pd::parse_ply(ply_header + "3 0 1 2\n\n  \n", "ok.ply").F.rows(), 1);
  EXPECT_EQ(pd::parse_ply(ply_header + "3 0 1 2\ncomment written by a tool 3 4 5\n", "c.ply").F.rows(), 1);
  EXPECT_EQ(pd::parse_ply(ply_header + "3 0 1 2\r\n" + std::string(1, '\0') + "\x1a", "z.ply").F.rows(), 1);
}
