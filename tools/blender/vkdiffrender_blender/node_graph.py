"""Reading Blender shader node trees into vkdiffrender values, and writing fitted values
back into the same nodes. Only attribute access on bpy objects; the formulas are in
mappings.py."""
import itertools

import bpy

from . import mappings

VOLUME_NODES = {"ShaderNodeVolumePrincipled", "ShaderNodeVolumeAbsorption", "ShaderNodeVolumeScatter"}


def output_node(tree, kind):
    """The Material Output (kind 'OUTPUT_MATERIAL') or World Output that Cycles uses, chosen
    as Blender's ntreeShaderOutputNode chooses for Cycles: an output for Cycles alone before
    one for all renderers, and within either the active one before the first."""
    candidates = [n for n in tree.nodes if n.type == kind and n.target in {"ALL", "CYCLES"}]
    ranked = sorted(candidates, key=lambda n: (n.target != "CYCLES", not n.is_active_output))
    return ranked[0] if ranked else None


def owner_output(owner):
    """The output node Cycles uses of a material's or World's node tree, or None (no
    owner, no nodes, no output)."""
    if owner is None or not owner.use_nodes:
        return None
    kind = "OUTPUT_WORLD" if owner.bl_rna.identifier == "World" else "OUTPUT_MATERIAL"
    return output_node(owner.node_tree, kind)


def live_links(socket):
    """The links into SOCKET that Cycles follows: not muted, and not invalid (Blender marks
    a link that closes a loop invalid)."""
    return [link for link in socket.links if link.is_valid and not link.is_muted] if socket.is_linked else []


def source_link(socket):
    """The link that feeds SOCKET as Cycles renders it, or None: a muted or invalid link
    feeds nothing, and a Reroute node passes on what feeds its input (a loop of Reroutes
    feeds nothing)."""
    seen = set()
    while socket is not None and socket.as_pointer() not in seen:
        seen.add(socket.as_pointer())
        links = live_links(socket)
        if not links:
            return None
        if links[0].from_node.bl_idname != "NodeReroute":
            return links[0]
        socket = links[0].from_node.inputs[0]
    return None


def is_fed(socket):
    """Whether a link feeds SOCKET as Cycles renders it (source_link): where none does,
    Cycles uses the socket's own value."""
    return source_link(socket) is not None


def linked_node(socket):
    """The node that feeds SOCKET (source_link), or None."""
    link = source_link(socket)
    return link.from_node if link else None


def attribute_input(node, name):
    """The attribute name an input reads when a geometry Attribute node's Fac feeds it
    directly (a volume grid of that name, in a Volume object), else None."""
    link = source_link(node.inputs[name])
    source = link.from_node if link else None
    if source is None or source.bl_idname != "ShaderNodeAttribute" or source.attribute_type != "GEOMETRY":
        return None
    return source.attribute_name if link.from_socket.name == "Fac" else None


def socket_value(socket):
    """A socket's own value: a float, or a tuple (a colour's RGBA)."""
    value = socket.default_value
    return tuple(value) if hasattr(value, "__len__") else float(value)


def folded_value(socket):
    """SOCKET's value where only constants feed it, as Cycles evaluates them: its own
    value where nothing feeds it, a Value or RGB node's, or a Math node's of such inputs
    (mappings.math_operation). A float feeding a colour is that grey, as in Cycles. None
    where anything else feeds it (a texture or attribute varies in space; other nodes are
    not evaluated), or a colour feeds a float."""
    link = source_link(socket)
    if link is None:
        return socket_value(socket)
    node = link.from_node
    if node.mute:
        return None
    if node.bl_idname in {"ShaderNodeValue", "ShaderNodeRGB"}:
        value = socket_value(link.from_socket)
    elif node.bl_idname == "ShaderNodeMath":
        # An input the operation does not use (not enabled) is not read.
        operands = [folded_value(s) if s.enabled else 0.0 for s in node.inputs]
        if any(not isinstance(v, float) for v in operands):
            return None
        value = mappings.math_operation(node.operation, operands)
        if value is None:
            return None
        if node.use_clamp:
            value = min(max(value, 0.0), 1.0)
    else:
        return None
    if isinstance(value, float) and socket.type == "RGBA":
        return (value, value, value, 1.0)
    return value if isinstance(value, float) == (socket.type == "VALUE") else None


def constant(node, name, warnings, what, overrides=None):
    """A node input's value, with constant nodes feeding it evaluated (folded_value); an
    input fed otherwise (a texture or attribute varies in space) cannot be expressed, so
    its unlinked value is used with a warning. `overrides` gives the values of inputs
    whose variation the caller exports otherwise (as a grid)."""
    if overrides and name in overrides:
        return overrides[name]
    socket = node.inputs[name]
    value = folded_value(socket)
    if value is not None:
        return value
    source = linked_node(socket)
    warnings.append(f"{what}: '{node.name}' input '{name}' is linked from '{source.name}' ({source.bl_idname}), "
                    f"which the export does not evaluate; its unlinked value is used")
    return socket_value(socket)


def volume_medium(node, warnings, what, overrides=None):
    """The medium of the closure tree under a Volume socket: Principled Volume, Volume
    Absorption, Volume Scatter, summed by Add Shader and weighted by Mix Shader.
    `overrides` as for constant(), for a Principled Volume's inputs."""
    if node is None:
        return None
    if node.mute:  # Cycles passes a muted node's closure input through, or nothing
        through = [link.from_socket for link in node.internal_links if link.from_socket.type == "SHADER"]
        return volume_medium(linked_node(through[0]), warnings, what, overrides) if through else None
    if node.bl_idname == "ShaderNodeVolumePrincipled":
        blackbody = node.inputs["Blackbody Intensity"]
        if is_fed(blackbody) or blackbody.default_value > 0.0:
            warnings.append(f"{what}: '{node.name}' Blackbody Intensity: blackbody emission is not supported "
                            f"by vkdiffrender and is dropped")
        inputs = ("Color", "Density", "Absorption Color", "Anisotropy", "Emission Color", "Emission Strength")
        return mappings.principled_volume_to_medium(*(constant(node, name, warnings, what, overrides)
                                                      for name in inputs))
    if node.bl_idname == "ShaderNodeVolumeAbsorption":
        return mappings.volume_absorption_to_medium(constant(node, "Color", warnings, what),
                                                    constant(node, "Density", warnings, what))
    if node.bl_idname == "ShaderNodeVolumeScatter":
        return mappings.volume_scatter_to_medium(constant(node, "Color", warnings, what),
                                                 constant(node, "Density", warnings, what),
                                                 constant(node, "Anisotropy", warnings, what))
    if node.bl_idname == "ShaderNodeAddShader":
        parts = [volume_medium(linked_node(s), warnings, what, overrides) for s in node.inputs]
        medium, exact = mappings.add_media([p for p in parts if p is not None])
        if not exact:
            warnings.append(f"{what}: '{node.name}' adds scattering of different anisotropies; "
                            f"exported as one lobe with their scattering-weighted mean g")
        return medium
    if node.bl_idname == "ShaderNodeMixShader":
        fac = min(max(constant(node, "Fac", warnings, what), 0.0), 1.0)
        parts = [volume_medium(linked_node(node.inputs[i]), warnings, what, overrides) for i in (1, 2)]
        weighted = [mappings.scale_medium(p, w) for p, w in zip(parts, (1.0 - fac, fac)) if p is not None]
        medium, exact = mappings.add_media(weighted)
        if not exact:
            warnings.append(f"{what}: '{node.name}' mixes scattering of different anisotropies; "
                            f"exported as one lobe with their scattering-weighted mean g")
        return medium
    warnings.append(f"{what}: volume node '{node.name}' ({node.bl_idname}) is not supported; ignored")
    return None


def volume_input(owner):
    """The Volume input of a material's or World's active output, or None."""
    out = owner_output(owner)
    return out.inputs["Volume"] if out else None


def has_volume(owner):
    """Whether a material or World renders a volume (of any shader)."""
    socket = volume_input(owner)
    return socket is not None and is_fed(socket)


def unsupported_volume_node(owner):
    """The node feeding OWNER's Volume output that the export cannot read (a node group,
    say), or None: Cycles still renders its volume, and no Surface beside it."""
    socket = volume_input(owner)
    node = linked_node(socket) if socket is not None else None
    readable = VOLUME_NODES | {"ShaderNodeAddShader", "ShaderNodeMixShader"}
    return node if node is not None and not node.mute and node.bl_idname not in readable else None


def material_volume_node(material):
    """The single volume node of a material or world whose Volume output it feeds directly
    (the node the Fit operator writes back into), else None."""
    socket = volume_input(material)
    node = linked_node(socket) if socket is not None else None
    return node if node is not None and node.bl_idname in VOLUME_NODES else None


def medium_of(owner, warnings, what, overrides=None):
    """The medium of a material's or world's Volume output, or None; `overrides` as for
    volume_medium()."""
    out = owner_output(owner)
    if out is None:
        return None
    medium = volume_medium(linked_node(out.inputs["Volume"]), warnings, what, overrides)
    if medium is None:
        return None
    g, clamped = mappings.clamp_g(medium.g)
    if clamped:
        warnings.append(f"{what}: anisotropy {medium.g:g} is outside vkdiffrender's [-0.99, 0.99]; clamped")
    return mappings.Medium(medium.sigma_a, medium.sigma_s, g, medium.emission)


def world_medium_name(world):
    """The scene medium's name: the World's, or "<World> (World)", "<World> (World 2)"...,
    the first that no material with a volume has (medium names must be unique)."""
    def taken(name):
        material = bpy.data.materials.get(name)
        return material is not None and material.users and medium_of(material, [], material.name) is not None

    candidates = itertools.chain([world.name, f"{world.name} (World)"],
                                 (f"{world.name} (World {n})" for n in itertools.count(2)))
    return next(name for name in candidates if not taken(name))


def surface_node(material):
    out = owner_output(material)
    return linked_node(out.inputs["Surface"]) if out else None


# The kinds of medium each volume node holds, with the inputs write_medium writes a fitted
# value of the kind to.
WRITTEN_INPUTS = {
    "ShaderNodeVolumePrincipled": {"sigma_a": ("Density", "Color", "Absorption Color", "Anisotropy"),
                                   "sigma_s": ("Density", "Color", "Absorption Color", "Anisotropy"),
                                   "g": ("Anisotropy",), "emission": ("Emission Color", "Emission Strength")},
    "ShaderNodeVolumeAbsorption": {"sigma_a": ("Density", "Color")},
    "ShaderNodeVolumeScatter": {"sigma_s": ("Density", "Color", "Anisotropy"), "g": ("Anisotropy",)},
}


def write_medium(node, medium, kinds=("sigma_a", "sigma_s", "g", "emission")):
    """Write a fitted medium into the node it came from, with the inverse mapping of that
    node's type, into the inputs that hold the fitted KINDS: the coefficients' inputs
    (Density, Color, Absorption Color) only where sigma_a or sigma_s was fitted, the
    Anisotropy where g was or they were, a Principled Volume's emission inputs only where
    emission was; the others, which may be linked, stay as they were. Returns warnings:
    where the node cannot hold the medium exactly, and inputs written that are linked
    (another node drives them, so Cycles does not use the value)."""
    warnings = []

    def write(name, value):
        socket = node.inputs[name]
        source = linked_node(socket)
        if source is not None:
            warnings.append(f"'{node.name}' input '{name}' is linked from '{source.name}'; the fitted value goes "
                            f"to its unlinked default, which Cycles does not use")
        socket.default_value = value

    if not {"sigma_a", "sigma_s"} & set(kinds):
        if "g" in kinds and "Anisotropy" in node.inputs:
            write("Anisotropy", medium.g)
        if "emission" in kinds and node.bl_idname == "ShaderNodeVolumePrincipled":
            values = mappings.medium_to_principled_volume(medium)
            write("Emission Color", (*values["emission_color"], 1.0))
            write("Emission Strength", values["emission_strength"])
        return warnings

    if node.bl_idname == "ShaderNodeVolumePrincipled":
        values = mappings.medium_to_principled_volume(medium)
        write("Density", values["density"])
        write("Color", (*values["color"], 1.0))
        write("Absorption Color", (*values["absorption_color"], 1.0))
        write("Anisotropy", values["anisotropy"])
        if "emission" in kinds:
            write("Emission Color", (*values["emission_color"], 1.0))
            write("Emission Strength", values["emission_strength"])
        return warnings
    if node.bl_idname == "ShaderNodeVolumeAbsorption":
        values = mappings.medium_to_volume_absorption(medium.sigma_a)
        write("Density", values["density"])
        write("Color", (*values["color"], 1.0))
        if max(medium.sigma_s) > 0.0:
            warnings.append(f"'{node.name}' is a Volume Absorption node: the fitted scattering is dropped")
        return warnings
    values = mappings.medium_to_volume_scatter(medium.sigma_s, medium.g)
    write("Density", values["density"])
    write("Color", (*values["color"], 1.0))
    write("Anisotropy", values["anisotropy"])
    if max(medium.sigma_a) > 0.0:
        warnings.append(f"'{node.name}' is a Volume Scatter node: the fitted absorption is dropped")
    return warnings


def set_light_value(light, value):
    """Sets a Blender light (its data) to a KHR_lights_punctual color x intensity: a sun's
    irradiance, or a point or spot light's radiant intensity, in Cycles' units."""
    if light.type == "SUN":
        sun = mappings.irradiance_to_sun(value)
        light.color, light.energy = sun["color"], sun["strength"]
    else:
        point = mappings.intensity_to_point_light(value)
        light.color, light.energy = point["color"], point["power"]
