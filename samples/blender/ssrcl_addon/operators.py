"""The add-on's two operators: set a scene up for ssrcl (the one button), and trace the frames
of the last render into the compositor (run by the render handler, or by hand)."""
import os

import bpy

from . import back_faces, compositor, export_camera, passes
from .handlers import written_frames
from .run_ssrcl import SsrclError, sidecar_path, trace


def _preferences(context):
    return context.preferences.addons[__package__].preferences


class SSRCL_OT_setup(bpy.types.Operator):
    """Enable the passes ssrcl needs, roughness, base colour and metallic AOVs in every material, a
    back-face depth view layer (exact surface thickness, about 1% of the render), a camera sidecar
    for every rendered frame, and the reflection pass traced after each render into the
    compositor, where it replaces Glossy Direct + Indirect"""
    bl_idname = "ssrcl.setup"
    bl_label = "Set Up ssrcl Reflection Pass"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        scene = context.scene
        settings = scene.render.image_settings
        # ssrcl reads every pass from one file; Blender keeps the data passes float in it.
        settings.file_format = 'OPEN_EXR_MULTILAYER'
        passes.enable_view_layer_passes(context.view_layer)
        scene.ssrcl.view_layer = context.view_layer.name
        wired = passes.wire_material_aovs(bpy.data.materials)
        if context.view_layer.name != back_faces.LAYER:
            back_faces.add_back_face_layer(scene)
        compositor.ensure_nodes(scene)
        scene.ssrcl.enabled = True
        self.report({'INFO'}, "ssrcl: passes on view layer '%s', back-face depth on '%s'; "
                    "roughness, base_color and metallic "
                    "AOVs added to %d Principled material(s), %d Glossy BSDF one(s) (metallic 1), "
                    "%d without either (roughness %g, metallic 0); the pass replaces Glossy "
                    "Direct + Indirect in the composite"
                    % (context.view_layer.name, back_faces.LAYER, len(wired["principled"]), len(wired["glossy"]),
                       len(wired["no_lobe"]), passes.NO_LOBE_ROUGHNESS))
        if wired["skipped"]:
            self.report({'WARNING'}, "ssrcl: materials without nodes write no AOVs (ssrcl reads "
                        "roughness 0, a mirror, and a black dielectric): %s"
                        % ", ".join(wired["skipped"]))
        return {'FINISHED'}


class SSRCL_OT_trace_render(bpy.types.Operator):
    """Run ssrcl on the frames the last render wrote (or on the Render Result, saved as a
    multilayer EXR at the output path) and load the pass into the compositor"""
    bl_idname = "ssrcl.trace_render"
    bl_label = "Trace Last Render with ssrcl"

    def _save_render_result(self, scene):
        """A render that wrote no file (F12): save it where an animation frame would go."""
        result = bpy.data.images.get("Render Result")
        if result is None or not result.has_data:
            raise SsrclError("no render to trace: render a frame first")
        if scene.render.image_settings.file_format != 'OPEN_EXR_MULTILAYER':
            raise SsrclError("the output format is not OpenEXR MultiLayer: press '%s' again"
                             % SSRCL_OT_setup.bl_label)
        path = os.path.abspath(bpy.path.abspath(scene.render.frame_path(frame=scene.frame_current)))
        os.makedirs(os.path.dirname(path), exist_ok=True)
        result.save_render(path, scene=scene)
        return [(scene.frame_current, path)]

    @staticmethod
    def _write_sidecars(scene, frames):
        """One camera sidecar per frame, beside its EXR, from the camera evaluated at that frame
        (as export_camera.py --frames does)."""
        current = scene.frame_current
        for frame, path in frames:
            scene.frame_set(frame)
            export_camera.write_camera_json(sidecar_path(path), scene)
        scene.frame_set(current)

    def execute(self, context):
        scene = context.scene
        prefs = _preferences(context)
        frames = written_frames.pop(scene.name, None)
        try:
            frames = frames or self._save_render_result(scene)
            self._write_sidecars(scene, frames)
            traced = [(frame, trace(prefs.executable, path, scene.ssrcl.view_layer,
                                    prefs.extra_arguments)) for frame, path in frames]
        except (SsrclError, RuntimeError, OSError) as e:  # ssrcl, the camera, the file system
            scene.ssrcl.status = str(e)
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        compositor.show_pass(scene, traced)
        scene.ssrcl.status = "traced %d frame(s): %s" % (len(traced), traced[0][1])
        self.report({'INFO'}, "ssrcl: " + scene.ssrcl.status)
        return {'FINISHED'}
