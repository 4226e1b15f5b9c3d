"""The compositor side: the ssrcl pass as an Image node, wired into the Composite output through a
"replace glossy" node group, where it takes the place of Cycles' Glossy Direct + Indirect (both
are in the glossy-pass form, Fresnel included), and into a Viewer through a "reflection over
environment" group (premultiplied pass over an environment colour: rgb + env * (1 - A))."""
import os

import bpy

GROUP_NAME = "ssrcl Reflection over Environment"
REPLACE_GROUP_NAME = "ssrcl Replace Glossy"
IMAGE_NODE = "ssrcl Reflection"
GROUP_NODE = "ssrcl Over Environment"
REPLACE_NODE = "ssrcl Replace Glossy"
LAYER_NODE = "ssrcl Render Layers"
VIEWER_NODE = "ssrcl Viewer"
# Mid grey: a visible stand-in until the user plugs in the scene's environment (sky colour, HDRI).
DEFAULT_ENVIRONMENT = (0.5, 0.5, 0.5, 1.0)


def reflection_group():
    """The node group, built once per file. Alpha Over without "Convert Premultiplied" is exactly
    the premultiplied over: foreground + background * (1 - foreground alpha)."""
    group = bpy.data.node_groups.get(GROUP_NAME)
    if group is not None:
        return group
    group = bpy.data.node_groups.new(GROUP_NAME, "CompositorNodeTree")
    group.inputs.new("NodeSocketColor", "Reflection")
    environment = group.inputs.new("NodeSocketColor", "Environment")
    environment.default_value = DEFAULT_ENVIRONMENT
    group.outputs.new("NodeSocketColor", "Image")
    inputs = group.nodes.new("NodeGroupInput")
    outputs = group.nodes.new("NodeGroupOutput")
    over = group.nodes.new("CompositorNodeAlphaOver")
    over.use_premultiply = False
    over.premul = 0.0
    inputs.location, over.location, outputs.location = (-300, 0), (0, 0), (300, 0)
    group.links.new(inputs.outputs["Environment"], over.inputs[1])  # background
    group.links.new(inputs.outputs["Reflection"], over.inputs[2])   # foreground
    group.links.new(over.outputs["Image"], outputs.inputs["Image"])
    return group


def replace_glossy_group():
    """The node group, built once per file: Combined holds Glossy Color x (Glossy Direct + Indirect);
    the ssrcl pass (rgb = its glossy light x A, A its confidence) takes their place where it found
    the reflection and keeps Cycles' own elsewhere:
        Image + Glossy Color x (Reflection - A x (Glossy Direct + Indirect))."""
    group = bpy.data.node_groups.get(REPLACE_GROUP_NAME)
    if group is not None:
        return group
    group = bpy.data.node_groups.new(REPLACE_GROUP_NAME, "CompositorNodeTree")
    for name in ("Image", "GlossDir", "GlossInd", "GlossCol", "Reflection"):
        group.inputs.new("NodeSocketColor", name)
    group.inputs.new("NodeSocketFloat", "Confidence")
    group.outputs.new("NodeSocketColor", "Image")
    inputs = group.nodes.new("NodeGroupInput")
    outputs = group.nodes.new("NodeGroupOutput")
    inputs.location, outputs.location = (-600, 0), (900, 0)

    def mix(blend, a, b, x):
        node = group.nodes.new("CompositorNodeMixRGB")
        node.blend_type, node.use_alpha, node.use_clamp = blend, False, False
        node.inputs[0].default_value = 1.0
        node.location = (x, 0)
        group.links.new(a, node.inputs[1])
        group.links.new(b, node.inputs[2])
        return node.outputs["Image"]

    i = inputs.outputs
    gloss = mix('ADD', i["GlossDir"], i["GlossInd"], -350)
    replaced = mix('MULTIPLY', gloss, i["Confidence"], -150)
    difference = mix('SUBTRACT', i["Reflection"], replaced, 50)
    coloured = mix('MULTIPLY', i["GlossCol"], difference, 250)
    group.links.new(mix('ADD', i["Image"], coloured, 450), outputs.inputs["Image"])
    return group


def _render_layers(tree, scene, view_layer):
    """The Render Layers node of `view_layer`: the scene's own where it has one."""
    node = next((n for n in tree.nodes if n.bl_idname == "CompositorNodeRLayers"
                 and n.scene == scene and n.layer == view_layer), None)
    if node is None:
        node = _node(tree, "CompositorNodeRLayers", LAYER_NODE, (-500, -250))
        node.scene, node.layer = scene, view_layer
    return node


def _node(tree, bl_idname, name, location):
    node = tree.nodes.get(name)
    if node is None or node.bl_idname != bl_idname:
        node = tree.nodes.new(bl_idname)
        node.name = node.label = name
        node.location = location
    return node


def ensure_nodes(scene):
    """Image node -> over-environment group -> Viewer, and Render Layers + Image node -> replace
    group -> Composite, in the scene's compositor; returns the Image node. The Composite output is
    the frame with the ssrcl pass in place of Glossy Direct + Indirect."""
    scene.use_nodes = True
    tree = scene.node_tree
    image = _node(tree, "CompositorNodeImage", IMAGE_NODE, (-200, -500))
    group = _node(tree, "CompositorNodeGroup", GROUP_NODE, (100, -500))
    group.node_tree = reflection_group()
    viewer = _node(tree, "CompositorNodeViewer", VIEWER_NODE, (400, -500))
    tree.links.new(image.outputs["Image"], group.inputs["Reflection"])
    tree.links.new(group.outputs["Image"], viewer.inputs["Image"])

    layers = _render_layers(tree, scene, scene.ssrcl.view_layer or bpy.context.view_layer.name)
    replace = _node(tree, "CompositorNodeGroup", REPLACE_NODE, (100, -250))
    replace.node_tree = replace_glossy_group()
    for name in ("Image", "GlossDir", "GlossInd", "GlossCol"):
        tree.links.new(layers.outputs[name], replace.inputs[name])
    tree.links.new(image.outputs["Image"], replace.inputs["Reflection"])
    tree.links.new(image.outputs["Alpha"], replace.inputs["Confidence"])
    composite = next((n for n in tree.nodes if n.bl_idname == "CompositorNodeComposite"), None)
    if composite is None:
        composite = _node(tree, "CompositorNodeComposite", "Composite", (400, -250))
    tree.links.new(replace.outputs["Image"], composite.inputs["Image"])
    return image


def show_pass(scene, frames_and_paths):
    """Loads the traced pass (one file, or a sequence for several frames) into the Image node."""
    node = ensure_nodes(scene)
    first_frame, first_path = frames_and_paths[0]
    image = bpy.data.images.load(first_path, check_existing=True)
    image.reload()  # a re-render rewrites the same file
    # ssrcl writes premultiplied RGB (RGB = found radiance x A): no conversion on load.
    image.alpha_mode = 'PREMUL'
    image.name = "ssrcl " + os.path.basename(first_path)
    node.image = image
    if len(frames_and_paths) > 1:
        image.source = 'SEQUENCE'
        last_frame = frames_and_paths[-1][0]
        # Image user frame = scene frame - start + 1 + offset: with these, file frame = scene frame.
        node.frame_start = first_frame
        node.frame_duration = last_frame - first_frame + 1
        node.frame_offset = first_frame - 1
    else:
        image.source = 'FILE'
    return node
