"""Add-on preferences (how to run ssrcl) and the per-scene state the handlers read."""
import bpy


class SsrclPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    executable: bpy.props.StringProperty(
        name="ssrcl executable", subtype='FILE_PATH', default="ssrcl",
        description="The ssrcl CLI: a path, or a name looked up on PATH")
    extra_arguments: bpy.props.StringProperty(
        name="Extra arguments", default="",
        description="Added to every `ssrcl trace` command, e.g. --quality high --seed 7")

    def draw(self, _context):
        self.layout.prop(self, "executable")
        self.layout.prop(self, "extra_arguments")


class SsrclSceneSettings(bpy.types.PropertyGroup):
    enabled: bpy.props.BoolProperty(
        name="Trace after render", default=False,
        description="Write camera sidecars while rendering and run ssrcl when the render is done")
    view_layer: bpy.props.StringProperty(
        name="View layer", default="ViewLayer",
        description="The view layer whose passes ssrcl reads (its channel prefix in the EXR)")
    status: bpy.props.StringProperty(name="Last ssrcl run", default="")
