#!/usr/bin/env bash
# Mutation check (issue 17): builds the library with deliberately wrong kernels and runs the tests
# that should notice. Each mutant is an exact text substitution in a copy of kernels/; the copy is
# embedded through the CMake cache variable SSRCL_KERNEL_SOURCE_DIR in a throwaway build directory,
# so the shipped kernels and the shipped library are never touched. A mutant is killed when one of
# its tests fails; a pattern that is not found is reported "not applied" and never counts as killed.
#
#   scripts/mutation-check.sh [--fast] [--build-dir DIR] [--only NAME]
#     --fast       the subset CI runs (a minute or two once the build directory exists)
#     --build-dir  throwaway build directory (default build-mutants/, reused between runs)
#     --only NAME  one mutant
# Ends with the line "K/N mutants killed"; exits 1 unless every mutant was killed.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="$ROOT/build-mutants"
FAST=0
ONLY=""
while [ $# -gt 0 ]; do
  case "$1" in
    --fast) FAST=1 ;;
    --build-dir) BUILD="$(realpath -m "$2")"; shift ;;
    --only) ONLY="$2"; shift ;;
    *) echo "mutation-check: unknown argument '$1' (use --fast, --build-dir DIR, --only NAME)" >&2; exit 2 ;;
  esac
  shift
done
MUTANT_KERNELS="$BUILD/mutant-kernels"
LOG="$BUILD/mutation-logs"

# Test sets: "executable:gtest-filter" entries, run in order until one fails. test_ggx_sampler
# compiles ggx.cl and sequence.cl into the host from SSRCL_KERNEL_SOURCE_DIR too, so it sees them.
MIRROR="test_mirror_analytic:*MatchesExactReflections*"
DIFFERENTIAL="test_differential:*"
GLOSSY_FAST="test_glossy_analytic:*FastPathBiasAndError*"
GLOSSY="test_glossy_analytic:*GlossySsr*"
HZB="test_hzb:*"
EDGE="test_mirror_analytic:*EdgeFade*"
SAMPLER="test_ggx_sampler:*"
HIGH="test_glossy_analytic:*HighPreset*"
DRAFT="test_glossy_analytic:*DraftStrideTwo*"
LINEAR_MAPPING="test_glossy_analytic:*LinearRoughnessMapping*"
THICKNESS="test_differential:*NonDefaultThickness*"
CREASE="test_glossy_analytic:*Crease*"
GLOSSY_HITS="test_glossy_hits:*"
HIDDEN="test_multiview:*HiddenReflectionsComeFromANeighbouringFrameToo*"
BACK="test_differential:*BackFaceDepth*"
FOOTPRINT="test_environment:*RippledFloor*"

# name | fast (1 = in the CI subset) | kernel file | exact pattern | replacement | tests
MUTANTS=(
  "thickness_x0.5|1|trace.cl|-g_in <= ray_q(ray, t_in).w|-g_in <= 0.5f * ray_q(ray, t_in).w|$DIFFERENTIAL $MIRROR"
  "thickness_x2|0|trace.cl|-g_in <= ray_q(ray, t_in).w|-g_in <= 2.0f * ray_q(ray, t_in).w|$DIFFERENTIAL $MIRROR"
  "no_backface_rejection|1|trace.cl|if (!(dot(plane.xyz, dir) < 0.0f)) {|if (false) {|$DIFFERENTIAL $MIRROR"
  "pdf_alpha_x1.05|1|ggx_lanes.cl|ggx_vndf_pdf_from_half_lanes(ol, h, alpha), above)|ggx_vndf_pdf_from_half_lanes(ol, h, 1.05f * alpha), above)|$GLOSSY_FAST $GLOSSY"
  "smith_g_dropped|0|resolve.cl|(lobe.c * lz + s)|(2.0f * lz)|$GLOSSY_FAST $GLOSSY"
  "smith_g_uncorrelated|0|resolve.cl|(lobe.c * lz + s)|(0.5f * (1.0f + lobe.c) * (lz + s))|$GLOSSY_FAST $GLOSSY"
  "ggx_d_alpha_linear|0|ggx_lanes.cl|float8 a2 = alpha * alpha;|float8 a2 = alpha;|$GLOSSY_FAST $GLOSSY"
  "hzb_max_reduction|1|hzb.cl|fmin(fmin(pyramid[i.x], pyramid[i.y]), fmin(pyramid[i.z], pyramid[i.w]))|fmax(fmax(pyramid[i.x], pyramid[i.y]), fmax(pyramid[i.z], pyramid[i.w]))|$HZB $DIFFERENTIAL"
  "back_min_reduction|1|back_pyramid.cl|fmax(fmax(a.y, b.y), fmax(d.y, e.y))|fmin(fmin(a.y, b.y), fmin(d.y, e.y))|$DIFFERENTIAL"
  "edge_fade_off|1|common.cl|if (!(edge_fade > 0.0f)) return 1.0f;|return 1.0f;|$EDGE"
  "reuse_weight_uniform|0|resolve.cl|return select((float8)(0.0f), w, lz > 0.0f);|return select((float8)(0.0f), (float8)(1.0f), lz > 0.0f);|$GLOSSY_FAST $GLOSSY"
  "sequence_rotation_off|0|sequence.cl|float2 u = r2 + shift;|float2 u = r2;|$GLOSSY_FAST $GLOSSY"
  "mirror_direction_flipped|0|ggx_lanes.cl|lanes3(2.0f * on * n.x - o.x, 2.0f * on * n.y - o.y, 2.0f * on * n.z - o.z)|lanes3(o.x - 2.0f * on * n.x, o.y - 2.0f * on * n.y, o.z - 2.0f * on * n.z)|$MIRROR"
  "vndf_radius_linear|0|ggx.cl|T r_ = sqrt(ux)|T r_ = (ux)|$SAMPLER $GLOSSY_FAST"
  "linear_mapping_squared|0|ggx.cl|return mapping == SSRCL_ROUGHNESS_LINEAR ? roughness : roughness * roughness;|return roughness * roughness;|$LINEAR_MAPPING"
  "filter_off|0|filter.cl|out_rgba[i] = filtered.w > 0.0f ? filtered : (float4)(0.0f);|out_rgba[i] = in_rgba[i];|$HIGH"
  "strided_pixels_unresolved|0|setup.cl|: strided_out              ? -1|: strided_out              ? 0|$DRAFT"
  "constant_thickness_ignored|0|setup.cl|float thickness_rel = params.adaptive_thickness ? 1.0f : params.thickness_rel;|float thickness_rel = params.adaptive_thickness ? 1.0f : 0.002f;|$THICKNESS"
  "neighbour_normal_check_off|0|resolve.cl|&& dot_lanes(f.nx, f.ny, f.nz, n_q.x, n_q.y, n_q.z) >= 0.9f|/* mutant */|$CREASE"
  "second_ray_finds_nothing|0|trace.cl|if (t2 < 0.0f) return (float4)(0.0f, 0.0f, 0.0f, -1.0f);|return (float4)(0.0f, 0.0f, 0.0f, -1.0f);|$GLOSSY_HITS"
  "clear_ignores_hidden|0|trace.cl|(t < 0.0f && !sc->hidden &&|(t < 0.0f && !sc->behind &&|$HIDDEN"
  "back_entry_off|0|trace.cl|if (sc->enters && h_in < 0.0f && h_out >= 0.0f &&|if (false &&|$BACK"
  "entry_angle_unbounded|0|trace.cl|{ return nq >= SSRCL_ENTRY_MIN_COS * sqrt(nn) * sqrt(qq); }|{ return 1; }|$DIFFERENTIAL"
  "skip_forgets_passage|0|trace.cl|const int8 beyond = p->active & (fmin(p->d_t, d_end) > hi);|const int8 beyond = 0;|$HIDDEN"
  "fill_point_sample|0|environment.cl|#define SSRCL_FILL_FOOTPRINT 0.21f|#define SSRCL_FILL_FOOTPRINT 0.0f|$FOOTPRINT"
)

echo "== building the test executables against mutable kernels in $BUILD"
mkdir -p "$MUTANT_KERNELS" "$LOG"
cp "$ROOT"/kernels/*.cl "$ROOT"/kernels/*.h "$MUTANT_KERNELS"/
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DSSRCL_KERNEL_SOURCE_DIR="$MUTANT_KERNELS" >"$LOG/configure.log"
targets() {
  local t
  for t in $1; do echo "--target ${t%%:*}"; done | sort -u
}
ALL_TESTS="$MIRROR $DIFFERENTIAL $GLOSSY $HZB $EDGE $SAMPLER $HIGH $DRAFT $LINEAR_MAPPING $THICKNESS $CREASE $GLOSSY_HITS $FOOTPRINT"
# shellcheck disable=SC2046
cmake --build "$BUILD" -j"$(nproc)" $(targets "$ALL_TESTS") >"$LOG/build.log" || {
  tail -30 "$LOG/build.log"; echo "mutation-check: the unmutated build failed" >&2; exit 2; }

# The unmutated kernels must pass every test set, or a "kill" would mean nothing.
run_tests() {  # prints the first failing entry, returns 1 when one failed
  local entry
  for entry in $1; do
    if ! (cd "$BUILD" && "./tests/${entry%%:*}" --gtest_filter="${entry#*:}" --gtest_brief=1) >"$LOG/$2.${entry%%:*}.log" 2>&1; then
      echo "$entry"
      return 1
    fi
  done
}
if failed=$(run_tests "$ALL_TESTS" baseline); then :; else
  echo "mutation-check: the unmutated kernels fail $failed (see $LOG/baseline.*.log)" >&2
  exit 2
fi

killed=0
total=0
printf '%-28s %-10s %-9s %s\n' mutant result seconds "killed by"
for m in "${MUTANTS[@]}"; do
  IFS='|' read -r name fast file pattern replacement tests <<<"$m"
  [ -n "$ONLY" ] && [ "$name" != "$ONLY" ] && continue
  [ "$FAST" = 1 ] && [ "$fast" != 1 ] && continue
  total=$((total + 1))
  cp "$ROOT"/kernels/*.cl "$ROOT"/kernels/*.h "$MUTANT_KERNELS"/
  if ! PAT="$pattern" REP="$replacement" perl -0pi -e '$n += s/\Q$ENV{PAT}\E/$ENV{REP}/g; END { exit($n ? 0 : 3) }' \
       "$MUTANT_KERNELS/$file"; then
    printf '%-28s %-10s %-9s %s\n' "$name" "NOT APPLIED" - "pattern not found in kernels/$file"
    continue
  fi
  start=$SECONDS
  # shellcheck disable=SC2046
  if ! cmake --build "$BUILD" -j"$(nproc)" $(targets "$tests") >"$LOG/$name.build.log" 2>&1; then
    printf '%-28s %-10s %-9s %s\n' "$name" "NOT BUILT" - "see $LOG/$name.build.log"
    continue
  fi
  if failed=$(run_tests "$tests" "$name"); then
    printf '%-28s %-10s %-9s %s\n' "$name" SURVIVED $((SECONDS - start)) "-"
  else
    killed=$((killed + 1))
    printf '%-28s %-10s %-9s %s\n' "$name" killed $((SECONDS - start)) "$failed"
  fi
done
[ "$total" -gt 0 ] || { echo "mutation-check: no mutant named '$ONLY'" >&2; exit 2; }
# Leave the throwaway build with the shipped kernels again.
cp "$ROOT"/kernels/*.cl "$ROOT"/kernels/*.h "$MUTANT_KERNELS"/
echo "$killed/$total mutants killed"
[ "$killed" = "$total" ]
