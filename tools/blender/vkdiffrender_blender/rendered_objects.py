"""The objects a render of the scene shows, found as Cycles finds them: in the collections
the view layer includes and that are enabled for rendering, not themselves disabled for
rendering, with collection instances expanded, so that a lamp from a linked asset lights
the scene at every place it is instanced."""
from typing import NamedTuple

import mathutils

# Instances of instances of ... deeper than this are not followed (a collection that
# instances itself would never end).
MAX_INSTANCE_DEPTH = 8


class RenderedObject(NamedTuple):
    object: object            # the Blender object (its data: the light, the volume)
    matrix_world: object      # where this instance of it is
    name: str                 # the object's name; for an instance, prefixed by its instancers'


def collection_objects(collection):
    """The objects of COLLECTION and of its child collections enabled for rendering."""
    if collection.hide_render:
        return
    yield from collection.objects
    for child in collection.children:
        yield from collection_objects(child)


def expand(obj, parent_matrix, prefix, depth):
    if obj.hide_render:
        return
    matrix = parent_matrix @ obj.matrix_world
    name = prefix + obj.name
    yield RenderedObject(obj, matrix, name)
    collection = obj.instance_collection if obj.instance_type == "COLLECTION" else None
    if collection is not None and depth < MAX_INSTANCE_DEPTH:
        placed = matrix @ mathutils.Matrix.Translation(-collection.instance_offset)
        for child in collection_objects(collection):
            yield from expand(child, placed, name + ".", depth + 1)


def layer_objects(layer_collection):
    if layer_collection.exclude or layer_collection.collection.hide_render:
        return
    yield from layer_collection.collection.objects
    for child in layer_collection.children:
        yield from layer_objects(child)


def rendered_objects(view_layer):
    """Every object VIEW_LAYER renders, once per place it is rendered at."""
    seen = set()
    for obj in layer_objects(view_layer.layer_collection):
        if obj.name in seen:
            continue  # linked into several collections
        seen.add(obj.name)
        yield from expand(obj, mathutils.Matrix.Identity(4), "", 0)
