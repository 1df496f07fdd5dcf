#include "render_session.hpp"

#include "point_text.hpp"

#include "commands.hpp"

#include "pushpull/deform/mesh_io.hpp"
#include "pushpull/renderer/camera.hpp"
#include "pushpull/renderer/colormap.hpp"
#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/geometry.hpp"
#include "pushpull/renderer/image_io.hpp"
#include "pushpull/renderer/offscreen_target.hpp"
#include "pushpull/renderer/renderer.hpp"
#include "pushpull/renderer/vk_check.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <string_view>

namespace pushpull::app {
namespace {

using namespace pushpull::renderer;
using Clock = std::chrono::steady_clock;

glm::vec3 to_glm(const std::vector<double>& v) {
  return {float(v[0]), float(v[1]), float(v[2])};
}
glm::vec3 to_glm(const Eigen::Vector3d& v) {
  return {float(v.x()), float(v.y()), float(v.z())};
}

// bounds in the render frame; o.eye and o.target in the model frame, moved by -origin (render_model.hpp).
View make_view(const RenderCommandOptions& o, const Bounds& bounds, float aspect,
               const Eigen::Vector3d& origin) {
  OrbitCamera orbit;
  // --up 1e300 1e300 1e300 is a direction, not three infinities: scaled by its stable norm first where the
  // plain one overflows (or underflows); other directions keep their bits.
  const Eigen::Vector3d up(o.up[0], o.up[1], o.up[2]);
  const double plain = up.norm();
  orbit.up = to_glm(plain > 0.0 && std::isfinite(plain) ? up : Eigen::Vector3d(up / up.stableNorm()));
  orbit.fov_y_deg = float(o.fov_deg);
  if (o.camera.size() >= 2) {
    orbit.azimuth_deg = float(o.camera[0]);
    orbit.elevation_deg = float(o.camera[1]);
  }
  if (o.camera.size() == 3) {
    if (!(o.camera[2] >= 1e-6 && o.camera[2] <= 1e6))
      throw UsageError("--camera: ZOOM must be from 1e-6 to 1e6 (1 frames the model)");
    orbit.distance_scale = float(1.0 / o.camera[2]);
  }
  View view = frame_bounds(bounds, orbit, aspect);
  if (!o.eye.empty() || !o.target.empty()) {
    auto render_frame = [&](const std::vector<double>& p) {
      return to_glm(Eigen::Vector3d(p[0], p[1], p[2]) - origin);
    };
    const glm::vec3 target = o.target.empty() ? bounds.centre() : render_frame(o.target);
    const glm::vec3 eye = o.eye.empty() ? glm::vec3(glm::inverse(view.view)[3]) : render_frame(o.eye);
    if (glm::length(eye - target) <= 0.0f) throw UsageError("--eye and --target coincide");
    // Looking along --up leaves the picture's up undefined (it came out blank).
    if (glm::length(glm::cross(glm::normalize(target - eye), orbit.up)) < 1e-4f)
      throw UsageError(
          "--up is parallel to the view direction (from --eye to --target): the picture's up "
          "is undefined; give another --up");
    view.view = glm::lookAt(eye, target, glm::normalize(orbit.up));
    const float distance = glm::length(eye - bounds.centre());
    const float radius = bounds.radius() > 0.0f ? bounds.radius() : 1e-6f;
    view.projection =
        perspective(glm::radians(orbit.fov_y_deg), aspect,
                    std::max(distance - 2.0f * radius, distance * 1e-3f), distance + 2.0f * radius);
  }
  return view;
}

// A camera that ends inside the model shows its inside (or nothing): say so, with where the eye is.
// Inside = generalised winding number >= 1/2 (inside a closed part); an orbit camera (no --eye) that
// ends inside the model's bounding box is reported too (parts of the model are behind it).
void warn_if_inside(const View& view, const RenderInputs& inputs, const Bounds& bounds, bool orbit) {
  const glm::vec3 eye(glm::inverse(view.view)[3]);
  const double winding = winding_number(inputs.positions, inputs.render->mesh.indices, eye);
  const bool in_box = glm::all(glm::greaterThan(eye, bounds.min)) && glm::all(glm::lessThan(eye, bounds.max));
  const double s = inputs.life_size_scale;
  const Eigen::Vector3d at = inputs.render->origin + Eigen::Vector3d(eye.x, eye.y, eye.z);  // model frame
  if (std::abs(winding) >= 0.5)
    std::fprintf(
        stderr,
        "pushpull render: warning: the camera is inside the model (eye at %s m, winding number %.2f): the "
        "picture shows the model from inside; use a smaller ZOOM in --camera or move --eye outside\n",
        point_in_metres_text(s * at).c_str(), winding);
  else if (orbit && in_box)
    std::fprintf(
        stderr,
        "pushpull render: warning: the orbit camera ends inside the model's bounding box (eye at %s m): "
        "parts of the model are behind it; use a smaller ZOOM in --camera\n",
        point_in_metres_text(s * at).c_str());
}

// Side by side: left | right.
TextureRGBA8 side_by_side(const TextureRGBA8& l, const TextureRGBA8& r) {
  TextureRGBA8 out;
  out.width = l.width + r.width;
  out.height = l.height;
  out.pixels.resize(size_t(out.width) * out.height * 4);
  for (uint32_t y = 0; y < out.height; ++y) {
    std::memcpy(&out.pixels[size_t(y) * out.width * 4], &l.pixels[size_t(y) * l.width * 4],
                size_t(l.width) * 4);
    std::memcpy(&out.pixels[(size_t(y) * out.width + l.width) * 4], &r.pixels[size_t(y) * r.width * 4],
                size_t(r.width) * 4);
  }
  return out;
}

void benchmark(Renderer& renderer, MeshId mesh, std::span<const View> views, std::span<const Draw> draws,
               const FrameSettings& settings, const RenderTargets& targets, const RenderInputs& inputs,
               int frames) {
  std::printf("benchmark: %zu triangles, %u vertices, %zu view(s) of %ux%u, %d frames per measurement\n",
              inputs.render->mesh.indices.size() / 3, inputs.render->mesh.vertex_count(), views.size(),
              targets.extent.width, targets.extent.height, frames);
  std::vector<float> positions = inputs.positions;
  std::vector<float> normals(positions.size());
  double normals_ms = 0.0;
  // Mean wall time per frame (CPU recording + lavapipe execution), GPU idle before and after.
  auto run = [&](bool upload, std::span<const Draw> frame_draws) {
    renderer.render(views, frame_draws, settings, targets);  // warm-up
    renderer.wait_idle();
    normals_ms = 0.0;
    const auto start = Clock::now();
    for (int f = 0; f < frames; ++f) {
      if (upload) {
        // A new deformation every frame: positions change, normals are recomputed on the CPU.
        const float wobble = 1.0f + 1e-4f * float(f % 2);
        for (float& x : positions) x *= wobble;
        const auto t0 = Clock::now();
        compute_vertex_normals(positions, inputs.render->mesh.indices, normals);
        normals_ms += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        renderer.update_vertices(mesh, positions, normals);
      }
      renderer.render(views, frame_draws, settings, targets);
    }
    renderer.wait_idle();
    normals_ms /= frames;
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count() / frames;
  };
  const double plain = run(false, draws);
  const double streamed = run(true, draws);
  const double streamed_normals = normals_ms;
  // The upload alone: frames that clear every view but draw nothing, with and without the upload.
  const double empty = run(false, {});
  const double empty_upload = run(true, {});
  const uint64_t bytes = renderer.last_upload_bytes();
  const char* views_text = views.size() == 2 ? "stereo" : views.size() == 1 ? "1 view" : "all views";
  std::printf("frame time, %s, no upload:             %9.2f ms\n", views_text, plain);
  std::printf("frame time, %s, full upload each frame: %9.2f ms (includes CPU normals %.2f ms)\n", views_text,
              streamed, streamed_normals);
  std::printf(
      "upload cost isolated (empty frames):        %9.2f ms per frame (%.2f -> %.2f ms; %.2f MB of "
      "positions + normals via the staging ring)\n",
      empty_upload - empty, empty, empty_upload, double(bytes) / 1e6);
  std::printf("  of which CPU normal recomputation:        %9.2f ms\n", normals_ms);
}

}  // namespace

struct PictureRenderer::Impl {
  std::shared_ptr<const RenderModel> render;
  Context context;
  std::unique_ptr<Renderer> renderer;  // after the context: destroyed before it
  std::unique_ptr<OffscreenTarget> target;
  MeshId model_mesh = 0;
  int arrow_material = -1, section_material = -1;
  std::vector<float> zero_scalars;
  std::vector<OverlayWeights> no_overlays;
  // The last picture's frame, for benchmark().
  std::vector<View> views;
  std::vector<Draw> draws;
  FrameSettings settings;

  Impl(std::shared_ptr<const RenderModel> model, int samples, bool validation)
      : render(std::move(model)), context(make_context(validation)) {
    RendererOptions renderer_options;
    renderer_options.samples = VkSampleCountFlagBits(samples);
    renderer = std::make_unique<Renderer>(context, renderer_options);
    std::vector<TextureId> texture_ids;
    for (const auto& t : render->textures) texture_ids.push_back(renderer->add_texture(t));
    auto tex = [&](int i) { return i >= 0 ? int(texture_ids[size_t(i)]) : -1; };
    std::vector<int> material_ids;
    for (Material m : render->materials) {
      m.base_colour_texture = tex(m.base_colour_texture);
      m.metallic_roughness_texture = tex(m.metallic_roughness_texture);
      m.normal_texture = tex(m.normal_texture);
      m.occlusion_texture = tex(m.occlusion_texture);
      m.emissive_texture = tex(m.emissive_texture);
      material_ids.push_back(int(renderer->add_material(m)));
    }
    RenderMesh mesh = render->mesh;
    mesh.normals = render->file_normals;
    for (auto& sub : mesh.submeshes)
      sub.material = sub.material >= 0 ? material_ids[size_t(sub.material)] : -1;
    // Streamed: every picture replaces its positions, normals, colour-map values and overlays.
    model_mesh = renderer->add_mesh(mesh, /*streamed=*/true);
    Material arrow;
    arrow.base_colour = glm::vec4(kArrowColour, 1.0f);
    arrow.unlit = true;  // the same colour in light and shadow, drawn on top of the surface
    arrow_material = int(renderer->add_material(arrow));
    Material section;
    section.base_colour = glm::vec4(kSectionColour, 1.0f);
    section.unlit = true;
    section_material = int(renderer->add_material(section));
    const size_t vertices = render->mesh.vertex_count();
    zero_scalars.assign(vertices, 0.0f);
    no_overlays.assign(vertices, OverlayWeights{});
  }

  static Context make_context(bool validation) {
    ContextOptions options;
    options.validation = validation;
    return Context::create(options);
  }
};

PictureRenderer::PictureRenderer(std::shared_ptr<const RenderModel> render, int samples, bool validation)
    : impl_(std::make_unique<Impl>(std::move(render), samples, validation)) {}

PictureRenderer::~PictureRenderer() = default;

std::size_t PictureRenderer::close() {
  impl_->target.reset();
  impl_->renderer.reset();
  return impl_->context.validation_message_count();
}

TextureRGBA8 PictureRenderer::render(const RenderInputs& inputs, const RenderCommandOptions& o) {
  Impl& p = *impl_;
  if (!p.renderer) throw CommandError("internal: a picture asked of a closed renderer");
  if (inputs.render != p.render)
    throw CommandError("internal: a picture's inputs were prepared for another model than its renderer's");
  const auto width = uint32_t(o.size[0]), height = uint32_t(o.size[1]);
  Renderer& renderer = *p.renderer;
  renderer.update_vertices(p.model_mesh, inputs.positions, inputs.normals,
                           inputs.scalars.empty() ? std::span<const float>(p.zero_scalars)
                                                  : std::span<const float>(inputs.scalars),
                           inputs.overlays.empty() ? std::span<const OverlayWeights>(p.no_overlays)
                                                   : std::span<const OverlayWeights>(inputs.overlays));

  Bounds bounds = compute_bounds(inputs.positions);
  if (inputs.frame) bounds = {inputs.frame->first, inputs.frame->second};
  const float size = bounds.radius() > 0.0f ? bounds.radius() : 1e-6f;
  std::vector<Draw> draws{Draw{p.model_mesh, glm::mat4(1.0f)}};
  if (inputs.arrow) {
    // Thick enough to see at the model's size, thin enough to stay an arrow for a short pull.
    const float length = float((inputs.arrow->second - inputs.arrow->first).norm());
    const float radius = std::clamp(0.08f * length, 0.004f * size, 0.02f * size);
    const RenderMesh arrow_mesh = make_arrow(to_glm(Eigen::Vector3d(inputs.arrow->first - p.render->origin)),
                                             to_glm(Eigen::Vector3d(inputs.arrow->second - p.render->origin)),
                                             radius, p.arrow_material);
    if (!arrow_mesh.indices.empty())
      draws.push_back({renderer.add_mesh(arrow_mesh), glm::mat4(1.0f), false, true});
  }
  if (!inputs.sections.empty())
    draws.push_back({renderer.add_mesh(make_tubes(inputs.sections, 0.0015f * size, p.section_material)),
                     glm::mat4(1.0f), false});

  FrameSettings settings;
  settings.up = to_glm(o.up);
  settings.lighting = !o.flat;
  const double unit_scale = 1000.0 * inputs.life_size_scale;  // model units -> life-size mm
  const std::string unit = "mm";
  const LegendLayout legend = legend_layout(width, height);
  renderer.set_legend(std::nullopt);
  if (o.color == "displacement") {
    settings.color_mode = ColorMode::displacement;
    double max = o.scalar_max.value_or(inputs.scalar_max);
    if (max <= 0.0) max = 1e-9;  // nothing moved: everything at the bottom of the map
    settings.scalar_max = float(max);
    if (!o.no_legend)
      renderer.set_legend(make_displacement_legend(float(max * unit_scale), "moved " + unit, legend.width_px,
                                                   legend.height_px),
                          legend.rect);
  } else if (o.color == "curvature-reversal") {
    settings.color_mode = ColorMode::curvature_sign;
    settings.curvature_epsilon = 0.5f;  // scalars: the new sign where it reversed, 0 where it was kept
    if (!o.no_legend)
      renderer.set_legend(
          make_sign_legend(legend.curvature_width_px, legend.height_px / 2, {"to K > 0", "to K < 0", "kept"}),
          legend.curvature_rect);
  } else if (o.color == "curvature-sign") {
    settings.color_mode = ColorMode::curvature_sign;
    settings.curvature_epsilon = 0.5f;  // scalars are the signs -1 / 0 / +1
    if (!o.no_legend)
      renderer.set_legend(make_curvature_legend(legend.curvature_width_px, legend.height_px / 2),
                          legend.curvature_rect);
  }

  const float aspect = float(width) / float(height);
  const View mono = make_view(o, bounds, aspect, p.render->origin);
  warn_if_inside(mono, inputs, bounds, o.eye.empty());
  std::vector<View> views{mono};
  if (o.ipd) {
    const auto eyes = stereo_pair(mono, float(*o.ipd));
    views.assign(eyes.begin(), eyes.end());
  }
  const auto layers = uint32_t(views.size());
  if (!p.target || p.target->extent().width != width || p.target->extent().height != height ||
      p.target->targets().views.size() != layers)
    p.target = std::make_unique<OffscreenTarget>(p.context, width, height, layers);
  renderer.render(views, draws, settings, p.target->targets());
  TextureRGBA8 image = p.target->read_back(0);
  if (views.size() == 2) image = side_by_side(image, p.target->read_back(1));
  p.views = std::move(views);
  p.draws = std::move(draws);
  p.settings = settings;
  return image;
}

void PictureRenderer::benchmark(const RenderInputs& inputs, const RenderCommandOptions& options) {
  Impl& p = *impl_;
  if (!p.renderer || !p.target || p.views.empty())
    throw CommandError("internal: benchmark before a picture was rendered");
  pushpull::app::benchmark(*p.renderer, p.model_mesh, p.views, p.draws, p.settings, p.target->targets(),
                           inputs, options.benchmark_frames);
}

namespace {
// Every pixel outside the legend's corner has the clear colour (sRGB-encoded, within 2 levels): the model is
// nowhere in the picture. (A view filled by one colour of the model is not taken for nothing.)
bool shows_nothing(const TextureRGBA8& image) {
  if (image.width == 0 || image.height == 0 ||
      image.pixels.size() < std::size_t(image.width) * image.height * 4)
    return false;
  const glm::vec4 clear = FrameSettings{}.clear_colour;
  auto encoded = [&](float linear) {
    return int(std::lround(255.0f * (image.srgb ? linear_to_srgb(linear) : std::clamp(linear, 0.0f, 1.0f))));
  };
  const int background[3] = {encoded(clear.r), encoded(clear.g), encoded(clear.b)};
  const LegendLayout legend = legend_layout(image.width, image.height);
  const auto legend_x1 =
      std::size_t(std::ceil(double(std::max(legend.rect[2], legend.curvature_rect[2])) * image.width)) + 2;
  const auto legend_y0 = std::size_t(std::max(0.0, std::floor(double(legend.rect[1]) * image.height) - 2));
  for (std::size_t y = 0; y < image.height; ++y)
    for (std::size_t x = 0; x < image.width; ++x) {
      if (x < legend_x1 && y >= legend_y0) continue;
      const uint8_t* pixel = &image.pixels[(y * image.width + x) * 4];
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(pixel[c]) - background[c]) > 2) return false;
    }
  return true;
}
}  // namespace

void render_to_png(const RenderInputs& inputs, const RenderCommandOptions& o) {
  TextureRGBA8 image;
  std::size_t validation_messages = 0;
  try {
    PictureRenderer pictures(inputs.render, o.samples, o.validation);
    image = pictures.render(inputs, o);
    if (o.benchmark_frames > 0) pictures.benchmark(inputs, o);
    validation_messages = pictures.close();
  } catch (const std::invalid_argument& e) {  // a sample count the device does not render
    throw CommandError("--samples " + std::to_string(o.samples) + ": " + e.what());
  } catch (const renderer::VulkanError& e) {
    // Out of memory: the size asked for is the likely cause, and the user's to change.
    if (e.result() != VK_ERROR_OUT_OF_DEVICE_MEMORY && e.result() != VK_ERROR_OUT_OF_HOST_MEMORY) throw;
    throw CommandError("--size " + std::to_string(o.size.at(0)) + " " + std::to_string(o.size.at(1)) +
                       (o.ipd ? " (two eyes)" : "") +
                       (o.samples > 1 ? " with " + std::to_string(o.samples) + " samples" : "") +
                       ": the picture does not fit in the Vulkan device's memory; a smaller --size (or "
                       "--samples) does (" +
                       e.what() + ")");
  }
  if (o.validation && validation_messages > 0)
    throw CommandError("Vulkan validation reported " + std::to_string(validation_messages) +
                       " message(s) (printed above)");
  if (shows_nothing(image)) {
    // Framed by us: our failure, not a result; said with its likely cause.
    if (o.eye.empty() && o.target.empty() && o.camera.size() < 3) {
      // (A model whose every triangle has zero area is refused as it loads.)
      std::string cause = "a model of an extreme scale, beyond what 32-bit floats draw?";
      if (o.size.size() == 2 && std::min(o.size[0], o.size[1]) < 8)
        cause = "--size " + std::to_string(o.size[0]) + " " + std::to_string(o.size[1]) +
                " is too small for it to cover a pixel's centre";
      throw CommandError(o.out + ": the picture would show nothing of the model (framed automatically: " +
                         cause + "); nothing written");
    }
    std::fprintf(stderr,
                 "pushpull render: warning: the picture shows nothing of the model (--eye/--target "
                 "look away from it, or --camera's zoom leaves it too small to see)\n");
  }
  write_picture(o.out, image);
  std::printf("pushpull render: wrote %s (%u x %u)\n", o.out.c_str(), image.width, image.height);
}

void write_picture(const std::filesystem::path& path, const TextureRGBA8& image) {
  try {
    const std::vector<uint8_t> bytes = encode_png(image, path.string());
    deform::write_file_atomically(
        path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  } catch (const std::exception& e) {
    throw CommandError(e.what());
  }
}

}  // namespace pushpull::app
