// The contract between the host and the kernels: constants, the HZB level table and each stage's
// parameters as one struct (passed by value, FidelityFX SSSR's constants block), compiled by both
// sides so they cannot drift apart. Plain C: only 4-byte scalars and arrays of them, so the layout
// is the same on the host and every OpenCL device. Variants (tracer, roughness mapping, counting
// mode) are not parameters but compile-time defines (host/pipeline/device_impl.hpp keys programs by them).
#ifndef SSRCL_SHARED_H
#define SSRCL_SHARED_H

#ifndef __OPENCL_VERSION__
#include <cstdint>
namespace ssrcl::shared {
typedef std::int32_t ssrcl_int;
typedef std::uint32_t ssrcl_uint;
#else
typedef int ssrcl_int;
typedef uint ssrcl_uint;
#endif

// Vector literals in the files the host compiles too (ggx.cl, sequence.cl; host/pipeline/opencl_c_on_host.hpp
// defines them for C++, where `(float3)(x, y, z)` would silently be a cast of a comma expression).
#ifdef __OPENCL_VERSION__
#define SSRCL_FLOAT2(x, y) ((float2)(x, y))
#define SSRCL_FLOAT3(x, y, z) ((float3)(x, y, z))
#endif

// Work is classified in tiles of SSRCL_TILE x SSRCL_TILE pixels, the 2D work-group size.
#define SSRCL_TILE 8
// Counting mode: per-ray texel reads summed over SSRCL_FETCH_SLOTS 32-bit slots (they cannot
// overflow on any frame; the host adds them in 64 bits), then SSRCL_HISTOGRAM_BINS power-of-two
// bins of iterations (bin b holds [2^(b-1), 2^b), bin 0 holds 0).
#define SSRCL_FETCH_SLOTS 1024
#define SSRCL_HISTOGRAM_BINS 33
// The counters setup fills: listed pixels, rays, listed tiles, pixels with rays.
#define SSRCL_COUNT_LISTED 0
#define SSRCL_COUNT_RAYS 1
#define SSRCL_COUNT_TILES 2
#define SSRCL_COUNT_TRACED 3
#define SSRCL_COUNTERS 4

// Values of the SSRCL_TRACER and SSRCL_ROUGHNESS_MAPPING program defines.
#define SSRCL_TRACER_HIZ 0
#define SSRCL_TRACER_LINEAR 1
#define SSRCL_TRACER_DDA 2
#define SSRCL_ROUGHNESS_SQUARED 0
#define SSRCL_ROUGHNESS_LINEAR 1

// The specular lobe's directional albedo E = F0 * scale + bias (include/ssrcl/specular_albedo.hpp)
// for hits on glossy surfaces with material passes (SSRCL_MATERIAL_HITS): (scale, bias) pairs over
// sqrt(GGX alpha) (rows) and sqrt(cos theta_o) (columns), SSRCL_ALBEDO_STEPS steps each from 0 to
// 1 inclusive. Square roots put the nodes where E bends: smooth lobes and grazing angles.
#define SSRCL_ALBEDO_STEPS 32

// Listed pixels a trace_rays work-item takes (kernels/trace.cl): its rays are traced in rounds of
// up to this many, in packets of eight float8 lanes.
#define SSRCL_TRACE_PIXELS 16

// One level of the HZB and colour pyramids: offset into the packed mip buffer and its size.
typedef struct {
  ssrcl_int offset;
  ssrcl_int width;
  ssrcl_int height;
  ssrcl_int pad;
} HzbLevel;

// Matrices are 16 floats in row-major order (the first four are the first row), acting on column
// vectors; the kernels load them as float16.

// What every stage's parameters begin with: the frame's camera, size and mirror cut-off, filled
// once per execute by the host (frameConstants, host/pipeline/stage_support.hpp).
typedef struct {
  float proj[16];
  float inv_proj[16];
  float normal_matrix[16];  // world -> view for normals (inverse transpose of the view's 3x3)
  ssrcl_int width, height;
  ssrcl_int tiles_x;        // SSRCL_TILE tiles across
  float near_plane, far_plane;
  float mirror_roughness;   // at or below: one mirror ray
} FrameConstants;

// kernels/setup.cl
typedef struct {
  FrameConstants frame;
  ssrcl_int color_channels;     // 3 or 4; only RGB is read
  float constant_roughness;     // >= 0 replaces the roughness image
  float max_roughness;          // rougher pixels get no ray
  ssrcl_int samples_per_pixel;  // rays per glossy pixel
  float full_rays_roughness;    // > 0: ray counts follow roughness up to this
  ssrcl_int trace_stride;       // 1, or 2: glossy rays in one pixel of each 2x2 block
  ssrcl_int classify;           // 0: every pixel and tile listed (the unclassified baseline)
  float thickness_rel;          // constant thickness model: share of depth
  ssrcl_int adaptive_thickness;  // 1: kernels/thickness.cl finishes the thickness
  ssrcl_int fill_normals;       // 1: write fill_normal_out (an environment fill follows)
  ssrcl_int edge_colors;        // 1: hits beside a nearer object's edge read the surface behind (edge_colour)
} SetupParams;

// kernels/thickness.cl
typedef struct {
  FrameConstants frame;
  ssrcl_int axis;  // 0: rows, 1: columns
  float scale, min_rel, max_rel;
  ssrcl_int orthographic;  // known_thickness: viewing lines along -z, not through the eye
} ThicknessParams;

// kernels/trace.cl (tracer, roughness mapping and counting mode are program defines)
typedef struct {
  FrameConstants frame;
  ssrcl_int level_count;   // HZB and colour pyramid levels
  ssrcl_int listed;        // pixels in the ray list
  ssrcl_int batch_size;    // samples per pixel in this pass's ray records
  ssrcl_int first_sample;  // sample index of the pass's first slot
  ssrcl_uint seed;
  float cone_scale;        // prefiltered hits: share of the lobe per ray; 0 reads full resolution
  float linear_step;       // linear tracer's step in pixels
  ssrcl_int max_iterations;
  float edge_fade;
  float glossy_hit_roughness;
  ssrcl_int has_base;      // base and specular images are bound
} TraceParams;

// Auxiliary views (kernels/view_trace.cl): rays the main frame leaves unresolved continue in other
// G-buffers of the scene. A ray tries at most SSRCL_VIEWS_PER_RAY views, best placed first.
#define SSRCL_MAX_VIEWS 16
#define SSRCL_VIEWS_PER_RAY 3
// Ray state per record, written by the trace with SSRCL_VIEWS: SSRCL_RAY_BEHIND while the ray's
// screen trace passed behind a surface before its hit or miss (the frame hid what it may have
// hit), SSRCL_RAY_THICK while its hit is one found behind a surface within its thickness (the
// surface may be in front of the real hit); the bits above hold the ray's source, 0 for the main
// frame, 1 + k for view k.
// SSRCL_RAY_CLEAR: a miss the trace followed to the frame's edge (not stopped by its step limit)
// in front of every surface on its way (facing it or not): nothing, shown or hidden, lies on that
// stretch, so views take it up only where it leaves the frame's frustum.
#define SSRCL_RAY_BEHIND 1
#define SSRCL_RAY_THICK 2
#define SSRCL_RAY_SOURCE_SHIFT 2
#define SSRCL_RAY_CLEAR 128

// One view's camera relative to the main one.
typedef struct {
  float from_main[16];  // main view space -> this view's space
  float to_main[16];    // its inverse
  float proj[16];
  ssrcl_int width, height;
  float near_plane, far_plane;
  // Rendered at another moment (a neighbouring frame): only what has not moved since is a hit.
  ssrcl_int other_time;
} ViewCamera;

typedef struct {
  FrameConstants frame;    // the main frame's
  ssrcl_int listed, batch_size, first_sample;  // as the trace's batch
  ssrcl_int view;          // the view this pass traces in
  ssrcl_int rank;          // rays for which it is their rank-th best view
  ssrcl_int rank_views;    // 1 in the first pass: it ranks every ray's views for all passes
  ssrcl_int view_count;
  ssrcl_int level_count;   // the view's HZB and colour levels
  ssrcl_int max_iterations;
  float cone_scale, linear_step, edge_fade;
  float radiance_limit;    // a view hit's mean rgb is scaled down to at most this (ViewStage::limitRadiance)
} ViewTraceParams;

// kernels/resolve.cl (roughness mapping is a program define)
typedef struct {
  FrameConstants frame;
  ssrcl_int batch_size, first_sample;
  ssrcl_int reuse_radius;
  ssrcl_int view_count;  // auxiliary views (programs built with SSRCL_VIEWS)
} ResolveParams;

// kernels/filter.cl
typedef struct {
  FrameConstants frame;
  ssrcl_int axes;  // 1: the taps along x only, 2: along y only, 3: the square (both)
} FilterParams;

// kernels/environment.cl (roughness mapping is a program define)
typedef struct {
  FrameConstants frame;
  float view_to_world[16];  // view-space directions into the environment's frame
  ssrcl_int level_count;    // prefiltered levels, one per roughness step
  float intensity;
} EnvironmentParams;

#ifndef __OPENCL_VERSION__
}  // namespace ssrcl::shared
#endif
#endif
