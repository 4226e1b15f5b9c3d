"""The render passes ssrcl reads: Z, Normal, the glossy light passes, and three AOVs written by
every material (ssrcl's default channel names, docs/inputs.md): roughness (value), and the
base_color (colour) and metallic (value) that give `ssrcl trace` the glossy-pass output form,
the quantity of Cycles' Glossy Direct + Indirect (Fresnel included), which the compositor then
replaces with it."""
from .scene_common import AOV_NAME, add_aov_output

BASE_COLOR_AOV, METALLIC_AOV = "base_color", "metallic"
# (AOV name, its type, the AOV node input it is written through)
AOVS = ((AOV_NAME, 'VALUE', "Value"), (BASE_COLOR_AOV, 'COLOR', "Color"),
        (METALLIC_AOV, 'VALUE', "Value"))

# Materials with no Principled BSDF and no Glossy BSDF have no GGX lobe ssrcl could trace: they
# write this roughness (the corpus convention, samples/corpus/make_corpus.py DIFFUSE_AOV), not the
# AOV's default 0, which ssrcl would read as a mirror. Cycles gives them no glossy light and a
# Glossy Color of 0, so the composite keeps nothing of their pass whatever F0 it has; metallic 0
# and a black base colour give the smallest F0 the form has (0.04) for a pass scored unweighted.
NO_LOBE_ROUGHNESS = 1.0
NO_LOBE_BASE_COLOR, NO_LOBE_METALLIC = (0.0, 0.0, 0.0, 1.0), 0.0
# A Glossy BSDF has no Fresnel in Cycles 3.4 and its colour goes to Glossy Color, not to Glossy
# Direct/Indirect: as a Principled BSDF it is metallic 1 with a white base colour (F0 = 1).
GLOSSY_BASE_COLOR, GLOSSY_METALLIC = (1.0, 1.0, 1.0, 1.0), 1.0


def enable_view_layer_passes(view_layer):
    view_layer.use_pass_z = True
    view_layer.use_pass_normal = True
    # ssrcl reads Cycles' glossy passes when present (the colour of glossy hits); the compositor
    # replaces Glossy Direct + Indirect with the pass.
    view_layer.use_pass_glossy_direct = True
    view_layer.use_pass_glossy_indirect = True
    view_layer.use_pass_glossy_color = True
    for name, kind, _ in AOVS:
        aov = next((a for a in view_layer.aovs if a.name == name), None)
        if aov is None:
            aov = view_layer.aovs.add()
            aov.name = name
        aov.type = kind


def _aovs_written(tree):
    return {n.name for n in tree.nodes if n.bl_idname == "ShaderNodeOutputAOV"}


def _constant(tree, bsdf, value, label, offset):
    """A Value node (a float) or an RGB node (a 4-tuple) holding `value`, beside `bsdf`."""
    node = tree.nodes.new("ShaderNodeValue" if isinstance(value, float) else "ShaderNodeRGB")
    node.label = label
    node.outputs[0].default_value = value
    if bsdf is not None:
        node.location = (bsdf.location.x - 250.0, bsdf.location.y - offset)
    return node.outputs[0]


def _input_source(tree, bsdf, name, offset):
    """The socket that drives input `name` of `bsdf`: its link, texture chains included, or for
    an unlinked input a Value/RGB node that then drives both the BSDF and the AOV, so editing
    that value later keeps them equal."""
    socket = bsdf.inputs[name]
    if socket.is_linked:
        return socket.links[0].from_socket
    value = socket.default_value
    source = _constant(tree, bsdf, float(value) if isinstance(value, float) else tuple(value),
                       "%s (BSDF + ssrcl AOV)" % name, offset)
    tree.links.new(source, socket)
    return source


def _first(tree, bl_idname):
    return next((n for n in tree.nodes if n.bl_idname == bl_idname), None)


def _material_sources(tree):
    """Which lobe a material's AOVs come from, and {AOV name: a function making its socket}
    (called only for the AOVs a material lacks, so no node is added for one it writes)."""
    bsdf = _first(tree, "ShaderNodeBsdfPrincipled")
    if bsdf is not None:
        return "principled", {AOV_NAME: lambda: _input_source(tree, bsdf, "Roughness", 300.0),
                              BASE_COLOR_AOV: lambda: _input_source(tree, bsdf, "Base Color", 450.0),
                              METALLIC_AOV: lambda: _input_source(tree, bsdf, "Metallic", 600.0)}
    glossy = _first(tree, "ShaderNodeBsdfGlossy")
    if glossy is not None:
        return "glossy", {
            AOV_NAME: lambda: _input_source(tree, glossy, "Roughness", 300.0),
            BASE_COLOR_AOV: lambda: _constant(tree, glossy, GLOSSY_BASE_COLOR, "ssrcl base colour", 450.0),
            METALLIC_AOV: lambda: _constant(tree, glossy, GLOSSY_METALLIC, "ssrcl metallic", 600.0)}
    return "no_lobe", {
        AOV_NAME: lambda: _constant(tree, None, NO_LOBE_ROUGHNESS, "ssrcl roughness", 0.0),
        BASE_COLOR_AOV: lambda: _constant(tree, None, NO_LOBE_BASE_COLOR, "ssrcl base colour", 0.0),
        METALLIC_AOV: lambda: _constant(tree, None, NO_LOBE_METALLIC, "ssrcl metallic", 0.0)}


def wire_material_aovs(materials):
    """Adds the roughness, base_color and metallic AOV outputs to every node material, each one it
    lacks (an AOV a material already writes is kept as it is). Returns
    {"principled": [...], "glossy": [...], "no_lobe": [...], "skipped": [...]}: material names by
    the lobe their AOVs come from, and materials without nodes (which write no AOV)."""
    wired = {"principled": [], "glossy": [], "no_lobe": [], "skipped": []}
    for mat in materials:
        if mat.is_grease_pencil:  # not rendered by Cycles: no AOV
            continue
        if not mat.use_nodes or mat.node_tree is None:
            wired["skipped"].append(mat.name)
            continue
        tree = mat.node_tree
        written = _aovs_written(tree)
        if all(name in written for name, _, _ in AOVS):
            continue
        lobe, sources = _material_sources(tree)
        for name, _, kind in AOVS:
            if name not in written:
                add_aov_output(mat, sources[name](), name, kind)
        wired[lobe].append(mat.name)
    return wired
