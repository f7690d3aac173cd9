"""The objects a render of the scene shows, found as Cycles finds them: in the collections
the view layer includes and that are enabled for rendering, not themselves disabled for
rendering, with collection instances expanded, so that a lamp from a linked asset lights
the scene at every place it is instanced. Objects instanced at a mesh's vertices or
faces, or by a particle system, are where the view layer's depsgraph places them; the
children of a vertex or face instancer are rendered only there, not at their own place."""
from typing import NamedTuple

import mathutils

# Instances of instances of ... deeper than this are not followed (a collection that
# instances itself would never end).
MAX_INSTANCE_DEPTH = 8

# The object types Blender's glTF exporter writes as meshes.
EXPORTED_GEOMETRY = frozenset({"MESH", "CURVE", "SURFACE", "FONT"})


class RenderedObject(NamedTuple):
    object: object            # the Blender object (its data: the light, the volume)
    matrix_world: object      # where this instance of it is
    name: str                 # the object's name; for an instance, prefixed by its instancers'
    in_collection_instance: bool  # placed by a collection instance (whose own instancers are not followed)


def collection_objects(collection):
    """The objects of COLLECTION and of its child collections enabled for rendering."""
    if collection.hide_render:
        return
    yield from collection.objects
    for child in collection.children:
        yield from collection_objects(child)


def shown_only_as_instances(obj):
    """Cycles renders the children of a vertex or face instancer at its vertices or faces
    alone."""
    return obj.parent is not None and obj.parent.instance_type in {"VERTS", "FACES"}


class Instances:
    """{instancer: [(object, world matrix) of each instance it places]} for the vertex,
    face, particle and collection instancers of the scene itself, as the view layer's
    depsgraph evaluates them; read from it once, when the first instancer asks."""

    def __init__(self, view_layer):
        self.view_layer = view_layer
        self.by_instancer = None

    def of(self, instancer):
        if self.by_instancer is None:
            depsgraph = self.view_layer.depsgraph
            depsgraph.update()  # the instances as the objects are now
            self.by_instancer = {}
            for instance in depsgraph.object_instances:
                if instance.is_instance and instance.parent is not None:
                    self.by_instancer.setdefault(instance.parent.original, []).append(
                        (instance.object.original, instance.matrix_world.copy()))
        return self.by_instancer.get(instancer, [])


def expand(obj, parent_matrix, prefix, depth, instances):
    if obj.hide_render:
        return
    matrix = parent_matrix @ obj.matrix_world
    name = prefix + obj.name
    yield RenderedObject(obj, matrix, name, depth > 0)
    if depth >= MAX_INSTANCE_DEPTH:
        return
    collection = obj.instance_collection if obj.instance_type == "COLLECTION" else None
    if collection is not None:
        placed = matrix @ mathutils.Matrix.Translation(-collection.instance_offset)
        # An object in several of the collection's children is instanced once, as Cycles does.
        for child in dict.fromkeys(collection_objects(collection)):
            if not shown_only_as_instances(child):
                yield from expand(child, placed, name + ".", depth + 1, instances)
    elif obj.is_instancer and depth == 0:
        for index, (instanced, place) in enumerate(instances.of(obj)):
            if not instanced.hide_render:
                yield RenderedObject(instanced, place, f"{name}.{index}.{instanced.name}", False)


def layer_objects(layer_collection):
    if layer_collection.exclude or layer_collection.collection.hide_render:
        return
    yield from layer_collection.collection.objects
    for child in layer_collection.children:
        yield from layer_objects(child)


def rendered_objects(view_layer):
    """Every object VIEW_LAYER renders, once per place it is rendered at."""
    instances = Instances(view_layer)
    seen = set()  # the objects themselves: a linked library's object may share a local one's name
    for obj in layer_objects(view_layer.layer_collection):
        if obj in seen:
            continue  # linked into several collections
        seen.add(obj)
        if not shown_only_as_instances(obj):
            yield from expand(obj, mathutils.Matrix.Identity(4), "", 0, instances)
