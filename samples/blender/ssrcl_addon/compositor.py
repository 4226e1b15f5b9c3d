"""The compositor side: the ssrcl pass as an Image node wired into a "reflection over
environment" node group (premultiplied pass over an environment colour: rgb + env * (1 - A))."""
import os

import bpy

GROUP_NAME = "ssrcl Reflection over Environment"
IMAGE_NODE = "ssrcl Reflection"
GROUP_NODE = "ssrcl Over Environment"
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


def _node(tree, bl_idname, name, location):
    node = tree.nodes.get(name)
    if node is None or node.bl_idname != bl_idname:
        node = tree.nodes.new(bl_idname)
        node.name = node.label = name
        node.location = location
    return node


def ensure_nodes(scene):
    """Image node -> group -> Viewer in the scene's compositor; returns the Image node.
    The Composite output is left alone: the pass is a reflection, not the finished frame."""
    scene.use_nodes = True
    tree = scene.node_tree
    image = _node(tree, "CompositorNodeImage", IMAGE_NODE, (-200, -500))
    group = _node(tree, "CompositorNodeGroup", GROUP_NODE, (100, -500))
    group.node_tree = reflection_group()
    viewer = _node(tree, "CompositorNodeViewer", VIEWER_NODE, (400, -500))
    tree.links.new(image.outputs["Image"], group.inputs["Reflection"])
    tree.links.new(group.outputs["Image"], viewer.inputs["Image"])
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
