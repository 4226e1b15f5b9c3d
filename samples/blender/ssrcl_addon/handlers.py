"""Render handlers: note every frame Blender writes, and once the render is over have the trace
operator write their camera sidecars and run ssrcl on them (scenes where Set Up was pressed)."""
import os
import sys

import bpy
from bpy.app.handlers import persistent

# Frames written by the render in progress, per scene: [(frame, absolute EXR path)].
written_frames = {}


@persistent
def _render_init(scene, _depsgraph=None):
    written_frames[scene.name] = []


@persistent
def _render_write(scene, _depsgraph=None):
    if not scene.ssrcl.enabled:
        return
    # No sidecar here: the render evaluates its own copy of the scene, so the camera of the main
    # depsgraph is not at this frame yet (and an interactive render runs this off the main thread).
    written_frames.setdefault(scene.name, []).append((scene.frame_current, _written_path(scene)))


def _written_path(scene):
    """The file the render just wrote: an animation frame's numbered path, or for a still
    (render(write_still=True)) the output path as given, with no frame number; the newer where
    both exist."""
    render = scene.render
    numbered = os.path.abspath(bpy.path.abspath(render.frame_path(frame=scene.frame_current)))
    still = os.path.abspath(bpy.path.abspath(render.filepath))
    if render.use_file_extension and not still.endswith(render.file_extension):
        still += render.file_extension
    written = [path for path in (numbered, still) if os.path.isfile(path)]
    return max(written, key=os.path.getmtime) if written else numbered


def _trace():
    # An ssrcl failure is reported by the operator (Info editor, panel) and comes back here as a
    # RuntimeError: printed, not raised, as a handler or timer has no caller to raise it to.
    try:
        bpy.ops.ssrcl.trace_render()
    except RuntimeError as e:
        print("ssrcl add-on:", e, file=sys.stderr)
    return None  # as a timer: do not repeat


@persistent
def _render_complete(scene, _depsgraph=None):
    if not scene.ssrcl.enabled:
        return
    _run_trace()


@persistent
def _render_cancel(scene, _depsgraph=None):
    # The frames an interrupted animation did write are complete: trace those, nothing else.
    if scene.ssrcl.enabled and written_frames.get(scene.name):
        _run_trace()


def _run_trace():
    if bpy.app.background:
        _trace()  # a blocking render on the main thread: run at once
    else:
        # An interactive render calls this from its own thread; data edits belong on the main one.
        bpy.app.timers.register(_trace, first_interval=0.0)


_HANDLERS = ((bpy.app.handlers.render_init, _render_init),
             (bpy.app.handlers.render_write, _render_write),
             (bpy.app.handlers.render_complete, _render_complete),
             (bpy.app.handlers.render_cancel, _render_cancel))


def register():
    for handlers, function in _HANDLERS:
        handlers.append(function)


def unregister():
    for handlers, function in _HANDLERS:
        if function in handlers:
            handlers.remove(function)
