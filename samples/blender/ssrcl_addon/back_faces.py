"""The back-face depth pass ssrcl reads for each pixel's exact surface thickness (docs/blender.md,
"Back-face depth"): a view layer whose material override lets every front face through
(Transparent BSDF) and stops at back faces, so Cycles' Z pass, which skips surfaces under the
view layer's alpha threshold, holds the depth of the first back face behind each pixel's visible
surface. Its only pass is Z and it needs one sample (Cycles writes Z from the first sample, the
same sub-pixel position as the main layer's at the same seed): about 1% of a render's cost."""
import bpy

LAYER = "BackFaces"  # ssrcl trace reads BackFaces.Depth.Z of the frame's own file with no option
MATERIAL = "ssrcl back faces"
SAMPLES = 1
TRANSPARENT_BOUNCES = 64  # front faces passed through before the ray gives up (Z stays 1e10)


def back_face_material():
    """Transparent on front faces, opaque black on back faces (the Geometry node's Backfacing)."""
    mat = bpy.data.materials.get(MATERIAL)
    if mat is not None:
        return mat
    mat = bpy.data.materials.new(MATERIAL)
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.clear()
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    mix = tree.nodes.new("ShaderNodeMixShader")
    front = tree.nodes.new("ShaderNodeBsdfTransparent")
    back = tree.nodes.new("ShaderNodeEmission")
    back.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
    tree.links.new(front.outputs["BSDF"], mix.inputs[1])
    tree.links.new(back.outputs["Emission"], mix.inputs[2])
    tree.links.new(mix.outputs["Shader"], out.inputs["Surface"])
    return mat


def make_back_face_layer(view_layer):
    """Makes a new `view_layer` (it has no AOVs) render only the back-face depth: Z alone, the
    override, one sample."""
    view_layer.material_override = back_face_material()
    view_layer.samples = SAMPLES
    view_layer.pass_alpha_threshold = 0.5
    view_layer.use_pass_combined = False
    view_layer.use_pass_z = True
    for name in ("use_pass_normal", "use_pass_glossy_direct", "use_pass_glossy_indirect",
                 "use_pass_glossy_color", "use_pass_object_index"):
        setattr(view_layer, name, False)


def add_back_face_layer(scene):
    """The BackFaces view layer beside the scene's (made once, kept in step on each call)."""
    layer = scene.view_layers.get(LAYER) or scene.view_layers.new(LAYER)
    make_back_face_layer(layer)
    scene.cycles.transparent_max_bounces = max(scene.cycles.transparent_max_bounces, TRANSPARENT_BOUNCES)
    return layer


def make_back_only_render(scene, layer="ViewLayer"):
    """Makes `scene` render the back-face depth alone, into a file of its own: the scene's `layer`
    is kept out of the render under another name and a new back-face layer takes the name, so the
    file's channel is <layer>.Depth.Z (what `ssrcl trace --back-depth-file` reads by default);
    32-bit ZIP multilayer EXR."""
    main = scene.view_layers[layer]
    main.name, main.use = "Scene", False
    make_back_face_layer(scene.view_layers.new(layer))
    scene.cycles.transparent_max_bounces = TRANSPARENT_BOUNCES
    # Blender writes Combined with every layer: black (no world, no emission) it compresses away.
    scene.world = bpy.data.worlds.new("ssrcl no world")
    scene.world.color = (0.0, 0.0, 0.0)
    scene.render.film_transparent = True
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth, settings.exr_codec = 'OPEN_EXR_MULTILAYER', '32', 'ZIP'
    scene.render.use_file_extension = False
