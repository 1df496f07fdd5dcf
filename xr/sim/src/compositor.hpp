// The simulated compositor: it checks submitted layers and, when PUSHPULL_XR_SIM_CAPTURE names a
// folder, writes what each eye would see (the first projection layer's sub-images) to PNG files
// "<folder>/frame_<NNNNNN>_<left|right>.png", and each quad layer's sub-image to
// "frame_<NNNNNN>_quad<K>.png" (the runtime does not reproject or blend layers into the eye images).
// Frame numbers count xrEndFrame calls from 0. Colour bytes are written as stored: an SRGB swapchain
// gives sRGB-encoded PNGs. Called from xrEndFrame with big_lock() held, on the application's queue.
#pragma once

#include "state.hpp"

#include <string>

namespace pushpull::xrsim {

// Validates the layers of an xrEndFrame; XR_SUCCESS or the spec's error for the first bad layer.
XrResult validate_layers(const Session& session, const XrFrameEndInfo& info);

// Writes the eyes (and quads) when this frame is to be captured. Returns the
// number of images written (0 when not capturing); failures are reported on stderr, not to the app.
int capture_frame(Session& session, const XrFrameEndInfo& info, int64_t frame_index);

}  // namespace pushpull::xrsim
