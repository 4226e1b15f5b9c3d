#pragma once
// Umbrella header: the whole public API.
#include "ssrcl/camera.hpp"
#include "ssrcl/device.hpp"
#include "ssrcl/environment.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/exr_output.hpp"
#include "ssrcl/frame.hpp"
#include "ssrcl/glossy_pass_form.hpp"
#include "ssrcl/image.hpp"
#include "ssrcl/io.hpp"
#include "ssrcl/pipeline.hpp"
#include "ssrcl/specular_albedo.hpp"
#include "ssrcl/version.hpp"
