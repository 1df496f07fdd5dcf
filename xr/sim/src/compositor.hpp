// The simulated compositor: it checks submitted layers and, when PUSHPULL_XR_SIM_CAPTURE names a
// folder, writes what each eye would see (the projection layer's sub-images) to PNG files
// "<folder>/frame_<NNNNNN>_<left|right>.png". Colour bytes are written as stored: an SRGB swapchain
// gives sRGB-encoded PNGs. Called from xrEndFrame with big_lock() held.
#pragma once

#include "state.hpp"

#include <string>

namespace pushpull::xrsim {

// Validates the layers of an xrEndFrame; XR_SUCCESS or the spec's error for the first bad layer.
XrResult validate_layers(const Session& session, const XrFrameEndInfo& info);

// Writes the eyes of the first projection layer when this frame is to be captured. Returns the
// number of images written (0 when not capturing); failures are reported on stderr, not to the app.
int capture_frame(Session& session, const XrFrameEndInfo& info, int64_t frame_index);

}  // namespace pushpull::xrsim
