// libFuzzer target for the model loader: any bytes, as GLB, glTF (embedded data only), Draco,
// OFF, OBJ or PLY, through load_model_from_memory (parse, decode, flatten, weld) and, when it
// loads, encode_glb. Must never crash, hang or allocate without bound; AssetError is the only
// acceptable failure.
#include <pushpull/assets/model.hpp>
#include <pushpull/assets/write.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> bytes(data, data + size);
  std::string name = "fuzz.obj";
  if (size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F')
    name = "fuzz.glb";
  else if (size >= 5 && std::string(reinterpret_cast<const char*>(data), 5) == "DRACO")
    name = "fuzz.drc";
  else if (size >= 1 && data[0] == '{')
    name = "fuzz.gltf";
  else if (size >= 3 && std::string(reinterpret_cast<const char*>(data), 3) == "OFF")
    name = "fuzz.off";
  else if (size >= 3 && std::string(reinterpret_cast<const char*>(data), 3) == "ply")
    name = "fuzz.ply";
  pushpull::assets::LoadOptions options;
  options.limits.max_vertices = 1'000'000;
  options.limits.max_triangles = 1'000'000;
  options.limits.max_instances = 10'000;
  try {
    const pushpull::assets::Model model = pushpull::assets::load_model_from_memory(bytes, name, {}, options);
    (void)pushpull::assets::encode_glb(model, model.deform_mesh.V, {}, nullptr);
  } catch (const pushpull::assets::AssetError&) {
  }
  return 0;
}
