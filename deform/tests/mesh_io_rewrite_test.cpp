// A deformed mesh written as a copy of its source file: only the positions change (polygons, attributes,
// comments and spacing stay), the new positions read back exactly, and layouts that cannot be rewritten in
// place fall back to triangles with a note.
#include "pushpull/deform/mesh_io.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pd = pushpull::deform;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("pushpull_mesh_rewrite_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A unit square as one quad plus a triangle on a fifth vertex: 5 vertices, 2 polygons (3 triangles).
Eigen::MatrixXd moved(Eigen::Index rows) {
  Eigen::MatrixXd V(rows, 3);
  for (Eigen::Index i = 0; i < rows; ++i) V.row(i) << 0.1 * double(i) + 1.0 / 3.0, -2.5e-17 * double(i), 7.0;
  return V;
}

}  // namespace

// OFF: the quad stays a quad, colours and comments stay, CRLF line ends stay; the positions read back
// exactly.
TEST(MeshIoRewrite, OffKeepsPolygonsColoursCommentsAndLineEnds) {
  const std::string source =
      "COFF\r\n# a quad and a triangle\r\n5 2 0\r\n"
      "0 0 0 255 0 0 255\r\n1 0 0 0 255 0 255  # corner\r\n1 1 0 0 0 255 255\r\n0 1 0 9 9 9 255\r\n"
      "2 0.5 0 1 2 3 4\r\n4 0 1 2 3\r\n3 1 4 2\r\n";
  const Eigen::MatrixXd V = moved(5);
  const pd::PositionRewrite rewrite = pd::rewrite_positions(source, pd::MeshFormat::off, V, "s.off");
  EXPECT_TRUE(rewrite.stale.empty());
  EXPECT_NE(rewrite.contents.find("\r\n4 0 1 2 3\r\n3 1 4 2\r\n"), std::string::npos) << rewrite.contents;
  EXPECT_NE(rewrite.contents.find("# a quad and a triangle\r\n5 2 0\r\n"), std::string::npos);
  EXPECT_NE(rewrite.contents.find(" 0 255 0 255  # corner\r\n"), std::string::npos) << rewrite.contents;
  const pd::Mesh back = pd::parse_off(rewrite.contents, "back.off");
  EXPECT_EQ(back.V, V);
  EXPECT_EQ(back.F.rows(), 3);
  // The same positions as the source's: the same bytes.
  Eigen::MatrixXd same(5, 3);
  same << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0.5, 0;
  EXPECT_EQ(pd::rewrite_positions(source, pd::MeshFormat::off, same, "s.off").contents, source);
}

// OBJ: texture coordinates, normals, groups, materials and faces with slashes stay; normals are named stale;
// a vertex's extra numbers (colour) stay.
TEST(MeshIoRewrite, ObjKeepsEverythingButPositionsAndNamesNormals) {
  const std::string source =
      "mtllib body.mtl\no body\nv 0 0 0 0.5 0.5 0.5\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
      "vn 0 0 1\ng panel\nusemtl paint\nf 1/1/1 2/2/1 3/3/1 4/1/1\nv 2 0.5 0\nf 2 5 3\n";
  const Eigen::MatrixXd V = moved(5);
  const pd::PositionRewrite rewrite = pd::rewrite_positions(source, pd::MeshFormat::obj, V, "s.obj");
  ASSERT_EQ(rewrite.stale.size(), 1u);
  EXPECT_EQ(rewrite.stale[0], "normals (vn)");
  for (const char* kept : {"mtllib body.mtl\no body\n", "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\ng panel\n",
                           "usemtl paint\nf 1/1/1 2/2/1 3/3/1 4/1/1\n", "\nf 2 5 3\n", " 0.5 0.5 0.5\n"})
    EXPECT_NE(rewrite.contents.find(kept), std::string::npos) << kept << "\n" << rewrite.contents;
  EXPECT_EQ(pd::parse_obj(rewrite.contents, "back.obj").V, V);
}

// PLY, ASCII and binary (both byte orders): other properties (normals, colours) and elements stay byte for
// byte; float coordinates take the nearest float.
TEST(MeshIoRewrite, PlyAsciiAndBinaryKeepOtherPropertiesAndElements) {
  const Eigen::MatrixXd V = moved(5);
  const std::string header_ascii =
      "ply\nformat ascii 1.0\ncomment kept\nelement vertex 5\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty uchar red\nelement face 2\n"
      "property list uchar int vertex_indices\nend_header\n";
  const std::string source = header_ascii +
                             "0 0 0 0.25 10\n1 0 0 0.25 20\n1 1 0 0.25 30\n0 1 0 0.25 40\n2 0.5 0 0.25 50\n"
                             "4 0 1 2 3\n3 1 4 2\n";
  const pd::PositionRewrite ascii = pd::rewrite_positions(source, pd::MeshFormat::ply, V, "s.ply");
  ASSERT_EQ(ascii.stale.size(), 1u);
  EXPECT_NE(ascii.contents.find(" 0.25 30\n"), std::string::npos) << ascii.contents;
  EXPECT_NE(ascii.contents.find("\n4 0 1 2 3\n3 1 4 2\n"), std::string::npos) << ascii.contents;
  EXPECT_EQ(pd::parse_ply(ascii.contents, "a.ply").V, V);  // text: exact even for float properties

  for (const bool little : {true, false}) {
    std::string binary =
        std::string("ply\nformat ") + (little ? "binary_little_endian" : "binary_big_endian") +
        " 1.0\nelement vertex 5\nproperty double x\nproperty float y\nproperty double z\n"
        "property uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    auto put = [&](const void* bytes, std::size_t size) {
      std::string chunk(static_cast<const char*>(bytes), size);
      if (little != (std::endian::native == std::endian::little)) std::reverse(chunk.begin(), chunk.end());
      binary += chunk;
    };
    for (int i = 0; i < 5; ++i) {
      const double x = i, z = -i;
      const float y = 0.5f;
      const unsigned char red = static_cast<unsigned char>(100 + i);
      put(&x, 8);
      put(&y, 4);
      put(&z, 8);
      binary += static_cast<char>(red);
    }
    binary += static_cast<char>(3);
    for (const int index : {0, 1, 2}) put(&index, 4);
    const pd::PositionRewrite rewrite = pd::rewrite_positions(binary, pd::MeshFormat::ply, V, "b.ply");
    ASSERT_EQ(rewrite.contents.size(), binary.size());
    const pd::Mesh back = pd::parse_ply(rewrite.contents, "b.ply");
    for (Eigen::Index i = 0; i < 5; ++i) {
      EXPECT_EQ(back.V(i, 0), V(i, 0));
      EXPECT_EQ(back.V(i, 1), double(float(V(i, 1))));
      EXPECT_EQ(back.V(i, 2), V(i, 2));
    }
    // Everything but the coordinates is the source's: the colours and the face.
    const std::size_t body = binary.find("end_header\n") + 11;
    for (int i = 0; i < 5; ++i)
      EXPECT_EQ(rewrite.contents[body + std::size_t(i) * 21 + 20], binary[body + std::size_t(i) * 21 + 20]);
    EXPECT_EQ(rewrite.contents.substr(body + 105), binary.substr(body + 105));
    EXPECT_EQ(rewrite.contents.substr(0, body), binary.substr(0, body));
  }
}

// A row of NaN keeps that vertex as written (a vertex the mesh does not use); other non-finite rows and a
// row count that does not fit the file are refused, naming the file.
TEST(MeshIoRewrite, NanRowsKeepTheirVertexAndMismatchesAreRefused) {
  const std::string source = "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n5.25 5.25 5.25\n3 0 1 2\n";
  Eigen::MatrixXd V = moved(4);
  V.row(3).setConstant(std::nan(""));
  const std::string text = pd::rewrite_positions(source, pd::MeshFormat::off, V, "s.off").contents;
  EXPECT_NE(text.find("\n5.25 5.25 5.25\n"), std::string::npos) << text;
  EXPECT_THROW((void)pd::rewrite_positions(source, pd::MeshFormat::off, moved(3), "s.off"), pd::MeshIoError);
  V(3, 0) = 1.0;  // partly NaN
  try {
    (void)pd::rewrite_positions(source, pd::MeshFormat::off, V, "s.off");
    ADD_FAILURE() << "a partly non-finite row was written";
  } catch (const pd::MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("s.off"), std::string::npos) << e.what();
  }
}

// write_deformed_mesh: the same format as the source gives its copy (the quad kept); another format, or a
// layout that cannot be rewritten in place (an ASCII PLY vertex over two lines), gives triangles, the latter
// with a note saying why.
TEST(MeshIoRewrite, WriteDeformedMeshCopiesTheSourceOrFallsBackToTriangles) {
  TempDir dir;
  const fs::path source = dir.path / "quad.off";
  std::ofstream(source) << "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  const pd::Mesh read = pd::read_mesh(source);
  pd::Mesh deformed = read;
  deformed.V(2, 2) = 0.125;
  EXPECT_TRUE(pd::write_deformed_mesh(dir.path / "out.off", source, deformed.V, deformed).empty());
  EXPECT_NE(file_text(dir.path / "out.off").find("\n4 0 1 2 3\n"), std::string::npos);
  EXPECT_EQ(pd::read_mesh(dir.path / "out.off").V, deformed.V);
  EXPECT_TRUE(pd::write_deformed_mesh(dir.path / "out.obj", source, deformed.V, deformed).empty());
  EXPECT_EQ(pd::read_mesh(dir.path / "out.obj").F.rows(), 2);  // triangles

  const fs::path integers = dir.path / "integers.ply";
  std::ofstream(integers) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty int x\nproperty int y\n"
                             "property int z\nelement face 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  pd::Mesh triangle = pd::read_mesh(integers);
  triangle.V(1, 2) = 0.5;  // not a whole number: integer coordinates cannot hold it
  const std::vector<std::string> notes =
      pd::write_deformed_mesh(dir.path / "out.ply", integers, triangle.V, triangle);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("written as triangles with positions only"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("integer coordinates"), std::string::npos) << notes[0];
  EXPECT_NE(file_text(dir.path / "out.ply").find("format ascii"), std::string::npos);  // as the source
  EXPECT_EQ(pd::read_mesh(dir.path / "out.ply").V, triangle.V);
}

// ASCII PLY is a stream of tokens (line breaks mean nothing to the reader): the rewrite finds each vertex's
// x, y and z where the reader does, across an element before the vertices written on one line, vertices split
// over lines, lists, and x, y, z not in that order; unmoved vertices keep their text.
TEST(MeshIoRewrite, AsciiPlyTokensAreFoundWhereTheReaderReadsThem) {
  const std::string source =
      "ply\nformat ascii 1.0\nelement camera 2\nproperty float focal\nelement vertex 4\nproperty float conf\n"
      "property float z\nproperty float x\nproperty float y\nelement face 2\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0.5 0.7\n"
      "0.9 0.000 0.000\n0.000\n0.9 0.000 1.000 0.000\n0.9 0.000 1.000 1.000 0.9 0.000 0.000 1.000\n"
      "3 0 1 2 3 0 2 3\n";
  const pd::Mesh read = pd::parse_ply(source, "s.ply");
  ASSERT_EQ(read.V.rows(), 4);
  Eigen::MatrixXd V = read.V;
  V(2, 2) = 0.25;  // vertex 2 (x 1, y 1) lifted
  const std::string text = pd::rewrite_positions(source, pd::MeshFormat::ply, V, "s.ply").contents;
  EXPECT_EQ(pd::parse_ply(text, "back.ply").V, V);
  EXPECT_EQ(pd::parse_ply(text, "back.ply").F, read.F);
  // Only vertex 2's z token changed; every other byte (the camera line, the split lines, the other
  // vertices' "0.000" texts, the faces) as it was.
  std::string expected = source;
  const std::string before = "0.9 0.000 1.000 1.000 0.9";
  expected.replace(expected.find(before), before.size(), "0.9 0.25 1.000 1.000 0.9");
  EXPECT_EQ(text, expected);
}

// A file that starts with a byte order mark keeps it, and its first vertex is the one rewritten first.
TEST(MeshIoRewrite, AByteOrderMarkStaysAndTheFirstVertexMoves) {
  const std::string source = "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  Eigen::MatrixXd V(3, 3);
  V << 0.5, 0, 0, 1, 0, 0, 0, 1, 0;
  const pd::PositionRewrite rewrite = pd::rewrite_positions(source, pd::MeshFormat::obj, V, "bom.obj");
  EXPECT_EQ(rewrite.contents, "\xEF\xBB\xBFv 0.5 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
}
