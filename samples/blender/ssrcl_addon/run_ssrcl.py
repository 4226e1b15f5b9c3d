"""Runs the ssrcl CLI on one rendered multilayer EXR; failures come back as SsrclError with
ssrcl's own message, for the operator to report."""
import os
import shlex
import subprocess

# ssrcl's exit codes (docs/cli.md, "Exit codes").
EXIT_MEANING = {1: "internal error", 2: "bad command line or unusable input",
                3: "OpenCL device problem", 4: "the output could not be written"}


class SsrclError(Exception):
    pass


def pass_path(exr_path):
    """Where the reflection pass of a render goes: an `ssrcl` folder beside it, same file name,
    so the frame number stays where Blender's image sequences look for it."""
    return os.path.join(os.path.dirname(exr_path), "ssrcl", os.path.basename(exr_path))


def sidecar_path(exr_path):
    """The camera sidecar ssrcl finds by itself: the EXR's stem + .camera.json."""
    return os.path.splitext(exr_path)[0] + ".camera.json"


def trace(executable, exr_path, view_layer, extra_args=""):
    """`ssrcl trace` on `exr_path` (camera from its sidecar) -> pass_path(exr_path).
    Default output names R,G,B,A,distance: Blender reads such a file as one RGBA image."""
    out_path = pass_path(exr_path)
    os.makedirs(os.path.dirname(out_path), exist_ok=True)
    try:
        extra = shlex.split(extra_args)
    except ValueError as e:
        raise SsrclError("extra ssrcl arguments '%s': %s" % (extra_args, e))
    command = [executable, "trace", exr_path, "-o", out_path, "--layer", view_layer] + extra
    try:
        result = subprocess.run(command, capture_output=True, text=True)
    except OSError as e:
        raise SsrclError("cannot run ssrcl '%s' (%s): set its path in the add-on preferences"
                         % (executable, e.strerror or e))
    if result.returncode != 0:
        message = (result.stderr.strip() or result.stdout.strip()).splitlines()
        raise SsrclError("ssrcl failed on %s (exit %d, %s): %s" % (
            os.path.basename(exr_path), result.returncode,
            EXIT_MEANING.get(result.returncode, "killed" if result.returncode < 0 else "error"),
            message[-1] if message else "no message"))
    return out_path
