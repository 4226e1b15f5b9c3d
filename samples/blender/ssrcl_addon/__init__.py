"""ssrcl Blender add-on: one button sets a scene up for ssrcl's screen-space reflection pass.

Set Up (Render properties > ssrcl Reflections) enables Z, Normal, the glossy passes and the
roughness, base_color and metallic AOVs wired into every material (from what drives its Principled
BSDF), and the multilayer EXR output; then every rendered frame gets its camera sidecar, ssrcl
traces the frames when the render is done (in the glossy-pass form, which those AOVs make its
default), and the pass appears in the compositor as an Image node that replaces Glossy Direct +
Indirect in the Composite output, and feeds a "reflection over environment" group on a Viewer.
"""
import bpy

from . import handlers, operators, preferences, ui

bl_info = {
    "name": "ssrcl Reflection Pass",
    "author": "ssrcl",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Render > ssrcl Reflections",
    "description": "Screen-space reflection pass from the render's G-buffer with the ssrcl CLI",
    "category": "Render",
}

_CLASSES = (preferences.SsrclPreferences, preferences.SsrclSceneSettings,
            operators.SSRCL_OT_setup, operators.SSRCL_OT_trace_render, ui.SSRCL_PT_render)


def register():
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.ssrcl = bpy.props.PointerProperty(type=preferences.SsrclSceneSettings)
    handlers.register()


def unregister():
    handlers.unregister()
    del bpy.types.Scene.ssrcl
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
