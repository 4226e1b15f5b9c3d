"""The ssrcl panel in the Render properties."""
import bpy

from .operators import SSRCL_OT_setup, SSRCL_OT_trace_render


class SSRCL_PT_render(bpy.types.Panel):
    bl_label = "ssrcl Reflections"
    bl_space_type = 'PROPERTIES'
    bl_region_type = 'WINDOW'
    bl_context = "render"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.ssrcl
        layout.operator(SSRCL_OT_setup.bl_idname)
        layout.prop(settings, "enabled")
        layout.operator(SSRCL_OT_trace_render.bl_idname)
        if settings.status:
            layout.label(text=settings.status)
