"""The render passes ssrcl reads: Z, Normal, the glossy light passes and a roughness value AOV
written by every Principled BSDF material (ssrcl's default channel names, docs/inputs.md)."""
from .scene_common import AOV_NAME, add_aov_output

# Materials with no Principled BSDF have no GGX lobe ssrcl could trace: they write this roughness
# (the corpus convention, samples/corpus/make_corpus.py DIFFUSE_AOV), not the AOV's default 0,
# which ssrcl would read as a mirror.
NO_LOBE_ROUGHNESS = 1.0


def enable_view_layer_passes(view_layer):
    view_layer.use_pass_z = True
    view_layer.use_pass_normal = True
    # ssrcl reads Cycles' glossy passes when present (the colour of glossy hits).
    view_layer.use_pass_glossy_direct = True
    view_layer.use_pass_glossy_indirect = True
    view_layer.use_pass_glossy_color = True
    aov = next((a for a in view_layer.aovs if a.name == AOV_NAME), None)
    if aov is None:
        aov = view_layer.aovs.add()
        aov.name = AOV_NAME
    aov.type = 'VALUE'


def _writes_roughness_aov(tree):
    return any(n.bl_idname == "ShaderNodeOutputAOV" and n.name == AOV_NAME for n in tree.nodes)


def _principled_roughness_source(tree):
    """The socket that drives the first Principled BSDF's roughness, or None without one.
    An unlinked roughness gets a Value node that then drives both the BSDF and the AOV, so
    editing that value later keeps them equal."""
    bsdf = next((n for n in tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled"), None)
    if bsdf is None:
        return None
    socket = bsdf.inputs["Roughness"]
    if socket.is_linked:
        return socket.links[0].from_socket
    value = tree.nodes.new("ShaderNodeValue")
    value.label = "Roughness (BSDF + ssrcl AOV)"
    value.location = (bsdf.location.x - 250.0, bsdf.location.y - 300.0)
    value.outputs[0].default_value = socket.default_value
    tree.links.new(value.outputs[0], socket)
    return value.outputs[0]


def wire_roughness_aov(materials):
    """Adds the roughness AOV output to every node material that lacks one.
    Returns (wired from a Principled BSDF, written as NO_LOBE_ROUGHNESS, materials without nodes)."""
    principled, no_lobe, skipped = [], [], []
    for mat in materials:
        if mat.is_grease_pencil:  # not rendered by Cycles: no AOV
            continue
        if not mat.use_nodes or mat.node_tree is None:
            skipped.append(mat.name)
            continue
        tree = mat.node_tree
        if _writes_roughness_aov(tree):
            continue
        source = _principled_roughness_source(tree)
        if source is None:
            value = tree.nodes.new("ShaderNodeValue")
            value.outputs[0].default_value = NO_LOBE_ROUGHNESS
            source = value.outputs[0]
            no_lobe.append(mat.name)
        else:
            principled.append(mat.name)
        add_aov_output(mat, source)
    return principled, no_lobe, skipped
