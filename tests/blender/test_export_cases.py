"""The add-on's export of what an artist's file may hold beyond the plain scenes of
scenes.py (export_cases_check.py builds each in headless Blender): lamps instanced from a
collection, lamps Cycles does not render, a mirrored area lamp, lamps whose node trees
change them, a World without nodes or with a mixed Surface, Volume objects whose names
clash as file names, a smoke simulation domain, glass, and paths and cameras the export
must refuse before writing anything. The exported scenes must load and render in
vkdiffrender."""
import base64
import json
import math
import pathlib
import struct
import subprocess

import numpy as np
import pytest
from conftest import run_blender_script
import vkdiffrender

HERE = pathlib.Path(__file__).resolve().parent


@pytest.fixture(scope="module")
def exported(blender, tmp_path_factory):
    out = tmp_path_factory.mktemp("cases")
    run_blender_script(blender, "export_cases_check.py", "--out", str(out))
    return out


def result(exported, case):
    return json.loads((exported / case / "result.json").read_text())


def document(exported, case):
    return json.loads((exported / case / "scene.gltf").read_text())


def own_warnings(exported, case):
    """The case's warnings but the one of Blender's default bounce limits, which every case keeps."""
    return [w for w in result(exported, case)["warnings"] if "bounce limits" not in w]


def area_emitter(doc, name):
    """(centre, unit normal of the first triangle) of an exported area light's polygon."""
    mesh = next(m for m in doc["meshes"] if m["name"] == name)
    primitive = mesh["primitives"][0]
    accessor = doc["accessors"][primitive["attributes"]["POSITION"]]
    view = doc["bufferViews"][accessor["bufferView"]]
    data = base64.b64decode(doc["buffers"][view["buffer"]]["uri"].split(",", 1)[1])
    points = np.array([struct.unpack_from("<3f", data, view["byteOffset"] + 12 * i) for i in range(accessor["count"])])
    normal = np.cross(points[1] - points[0], points[2] - points[0])
    return points.mean(axis=0), normal / np.linalg.norm(normal)


def render_mean(cli, exported, case, scene="scene.gltf"):
    """vkdiffrender's image mean of the exported scene (16x16, 16 spp), which must load."""
    image = exported / case / "render.exr"
    run = subprocess.run([cli, "render", str(exported / case / scene), "-o", str(image), "--width", "16",
                          "--height", "16", "--spp", "16", "--max-depth", "2"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    pixels = vkdiffrender.read_image(str(image))
    assert np.isfinite(pixels).all()
    return float(pixels.mean())


def test_lamps_instanced_from_a_collection_are_exported_at_the_instance(exported, cli):
    doc = document(exported, "instanced_lights")
    bulb = doc["extensions"]["KHR_lights_punctual"]["lights"][0]
    assert bulb["intensity"] == pytest.approx(200.0 / (4.0 * math.pi))  # Cycles' watts, not the exporter's candela
    assert sum(m["name"] == "Lamps.Panel.area" for m in doc["meshes"]) == 1  # in two collections of the asset
    centre, normal = area_emitter(doc, "Lamps.Panel.area")
    assert centre == pytest.approx([1.0, 2.5, 0.0], abs=1e-6)  # Blender (1, 0, 2.5): the instance's offset
    assert normal == pytest.approx([0.0, -1.0, 0.0], abs=1e-6)  # emitting down, its local -Z
    assert render_mean(cli, exported, "instanced_lights") > 0.0


def test_lamps_instanced_at_vertices_are_exported_at_each_vertex_and_not_at_their_own_place(exported, cli):
    # One lamp's instances are one light data: a value fitted to one is written for all.
    assert result(exported, "vertex_instanced_lights")["instanced_write_back_warnings"] == [
        "lights/Row.0.Panel.area/emission: its light data is shared with Row.1.Panel.area, which takes the value too"]
    doc = document(exported, "vertex_instanced_lights")
    for index, x in enumerate((-1.5, 1.5)):
        centre, _ = area_emitter(doc, f"Row.{index}.Panel.area")
        assert centre == pytest.approx([x, 2.5, 0.0], abs=1e-6)  # Blender (x, 0, 2.5)
    assert not any(m["name"] == "Panel.area" for m in doc["meshes"])
    bulbs = [n["translation"] for n in doc["nodes"] if "KHR_lights_punctual" in n.get("extensions", {})]
    assert sorted(bulbs) == [pytest.approx([-1.5, 3.0, 0.0]), pytest.approx([1.5, 3.0, 0.0])]
    assert not any("instances" in w for w in own_warnings(exported, "vertex_instanced_lights"))
    assert render_mean(cli, exported, "vertex_instanced_lights") > 0.0


def triangles(doc, node_name):
    mesh = doc["meshes"][next(n["mesh"] for n in doc["nodes"] if n.get("name") == node_name)]
    return sum(doc["accessors"][p["indices"]]["count"] // 3 for p in mesh["primitives"])


def test_modifiers_are_exported_as_the_render_evaluates_them_and_left_as_they_were(exported):
    doc = document(exported, "render_modifiers")
    assert triangles(doc, "Rendered") == 2 * 6 * 4 * 2  # two copies of a cube subdivided once
    assert triangles(doc, "Viewport") == 6 * 2  # its Array is for the viewport only
    # Disabled in viewports, whose depsgraph does not evaluate them: subdivided all the same.
    assert triangles(doc, "Disabled") == 6 * 4 * 2
    assert triangles(doc, "InDisabled") == 6 * 4 * 2
    assert result(exported, "render_modifiers")["modifiers_after"] == {
        "Rendered": [["Subdivision", True, True, 0], ["Array", False, True, None]],
        "Viewport": [["Array", True, False, None]],
        "Disabled": [["Subdivision", True, True, 0]], "InDisabled": [["Subdivision", True, True, 0]]}
    assert result(exported, "render_modifiers")["viewport_after"] == [True, True, 0]
    assert own_warnings(exported, "render_modifiers") == []


def test_colour_attributes_are_not_exported_as_vertex_colours(exported):
    doc = document(exported, "vertex_colours")
    assert not any("COLOR_0" in p["attributes"] for m in doc["meshes"] for p in m["primitives"])


def accessor_values(exported, case, doc, index):
    """Accessor INDEX of the case's scene.bin as floats, one row an element (normalized
    integers read as fractions)."""
    accessor = doc["accessors"][index]
    view = doc["bufferViews"][accessor["bufferView"]]
    data = (exported / case / doc["buffers"][view["buffer"]]["uri"]).read_bytes()
    dtype = {5126: "<f4", 5123: "<u2", 5121: "u1"}[accessor["componentType"]]
    width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[accessor["type"]]
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    stride = view.get("byteStride", width * np.dtype(dtype).itemsize) // np.dtype(dtype).itemsize
    values = np.frombuffer(data, dtype=dtype, offset=start, count=(accessor["count"] - 1) * stride + width)
    values = np.lib.stride_tricks.as_strided(values, (accessor["count"], width),
                                             (stride * values.itemsize, values.itemsize)).astype(float)
    if dtype != "<f4" and accessor.get("normalized"):
        values /= np.iinfo(dtype).max
    return values


def vertex_colour_of(exported, case, doc, mesh_name, primitive=0):
    """The one colour (RGB, linear) of every vertex of the primitive's COLOR_0 (None without
    it) in the case's scene.bin; the cubes of read_colour_attributes are of one colour each."""
    primitives = next(m for m in doc["meshes"] if m["name"] == mesh_name)["primitives"]
    index = primitives[primitive]["attributes"].get("COLOR_0")
    if index is None:
        return None
    values = accessor_values(exported, case, doc, index)[:, :3]
    assert np.ptp(values, axis=0).max() < 1e-3, values
    return values[0]


def test_colour_attributes_that_materials_read_are_exported_where_they_are_read(exported, cli):
    case = "read_colour_attributes"
    doc = document(exported, case)
    assert vertex_colour_of(exported, case, doc, "Rendered") == pytest.approx([0.1] * 3, abs=1e-3)
    # The attribute the node names, not the render one; the render one is set back after.
    assert vertex_colour_of(exported, case, doc, "Named") == pytest.approx([0.2] * 3, abs=1e-3)
    assert result(exported, case)["render_colour_attributes_after"]["Named"] == 0
    assert vertex_colour_of(exported, case, doc, "Unread") is None
    assert vertex_colour_of(exported, case, doc, "Missing") is None
    # Its materials read A and B: both primitives get A (0.1), with a warning.
    assert len(next(m for m in doc["meshes"] if m["name"] == "TwoRead")["primitives"]) == 2
    for primitive in (0, 1):
        assert vertex_colour_of(exported, case, doc, "TwoRead", primitive) == pytest.approx([0.1] * 3, abs=1e-3)
    # Two objects of one mesh, each with a material of its own: both read their colours.
    shared = [p for m in doc["meshes"] if m["name"].startswith("Shared") for p in m["primitives"]]
    assert len(shared) == 2 and all("COLOR_0" in p["attributes"] for p in shared), doc["meshes"]
    warnings = own_warnings(exported, case)
    assert any("'Missing'" in w and "'Absent', which is not among the mesh's colour attributes" in w
               for w in warnings), warnings
    assert any("'TwoRead'" in w and "all read 'A'" in w for w in warnings), warnings
    assert len(warnings) == 2 + sum("Principled BSDF is exported as a Lambertian" in w for w in warnings), warnings
    assert np.isfinite(render_mean(cli, exported, case))


def test_a_colour_attribute_painted_face_by_face_is_exported_at_each_corner(exported):
    """Blender 3.4's glTF exporter reads a face-corner attribute at the wrong corners; each
    exported vertex must carry the colour of its own face (known from its flat normal)."""
    case = "corner_colour_attribute"
    doc = document(exported, case)
    (primitive,) = next(m for m in doc["meshes"] if m["name"] == "Painted")["primitives"]
    normals = accessor_values(exported, case, doc, primitive["attributes"]["NORMAL"])
    colours = accessor_values(exported, case, doc, primitive["attributes"]["COLOR_0"])[:, :3]
    blender_normals = np.stack([normals[:, 0], -normals[:, 2], normals[:, 1]], axis=1)  # glTF is y-up
    expected = 0.5 + 0.4 * blender_normals
    # Byte colours hold 8-bit sRGB values: half a step is at most 0.0042 in linear (at 0.9,
    # where the curve is steepest of these colours).
    assert np.abs(colours - expected).max() < 0.005, np.abs(colours - expected).max()
    assert len(np.unique(np.round(colours, 2), axis=0)) == 6
    # The slot no face uses reads an attribute the mesh lacks, but Cycles never shades it.
    assert [w for w in own_warnings(exported, case) if "Principled BSDF is exported as a Lambertian" not in w] == []


def test_the_fit_offers_only_what_optimize_can_step_in_log_units(exported):
    fittable = result(exported, "fit_parameters")["fittable"]
    assert "materials/Grey/base_color" in fittable and "lights/Lit.area/emission" in fittable, fittable
    assert "materials/Red/base_color" not in fittable  # a channel of 0 has no logarithm
    assert "materials/Foggy/base_color" not in fittable  # a medium's boundary has no colour
    assert "media/Foggy/sigma_s" in fittable
    assert "lights/Dark.area/emission" not in fittable  # 0 W
    assert "materials/HiddenOnly/base_color" not in fittable  # on no rendered object: not exported
    # A value fed by a node would be written where Cycles does not use it.
    assert "materials/Computed/base_color" not in fittable
    assert "media/ComputedFog/g" in fittable and "media/ComputedFog/sigma_s" not in fittable


def test_a_fitted_punctual_light_goes_to_the_lamp_whose_data_the_export_named_it_after(exported):
    assert result(exported, "light_write_back")["exported_lights"] == ["Light", "Light.001"]
    watts = result(exported, "light_write_back")["light_watts"]
    assert watts["Key"] == pytest.approx(4.0 * math.pi)  # 1 W/sr in every direction
    assert watts["Light"] == 100.0


def test_a_fit_of_g_alone_writes_the_anisotropy_and_leaves_the_linked_density(exported):
    after = result(exported, "medium_write_back")["volume_after"]
    assert after == {"anisotropy": pytest.approx(0.5), "density": 3.0, "unchanged": True}
    warnings = result(exported, "medium_write_back")["write_back_warnings"]
    assert len(warnings) == 1 and warnings[0].startswith("media/Smoke/density: a grid's fitted voxels"), warnings


def test_volumes_that_cycles_adds_up_are_reported(exported):
    warnings = own_warnings(exported, "added_volumes")
    world = [w for w in warnings if w.startswith("world 'Fog'")]
    assert len(world) == 1 and all(f"'{name}'" in world[0] for name in ("Outer", "Overlapping", "Apart"))
    overlaps = [w for w in warnings if "boxes overlap" in w]
    assert overlaps == ["objects 'Outer' and 'Overlapping': their volumes' boxes overlap; where the volumes do, "
                        "Cycles adds them and vkdiffrender has the inner one's medium alone"]


def test_lamps_that_cycles_does_not_render_are_not_exported_and_a_mirrored_one_still_shines_down(exported, cli):
    doc = document(exported, "hidden_lights")
    emitters = [m["name"] for m in doc["meshes"] if m["name"].endswith(".area")]
    assert emitters == ["Mirrored.area"]
    assert any("'Portal': a light portal is not exported" in w for w in own_warnings(exported, "hidden_lights"))
    emitter = next(m for m in doc["materials"] if m["name"] == "Mirrored.area")
    assert emitter["pbrMetallicRoughness"]["metallicFactor"] == 0.0  # glTF's default, 1, is metal
    _, normal = area_emitter(doc, "Mirrored.area")
    assert normal == pytest.approx([0.0, -1.0, 0.0], abs=1e-6)
    assert render_mean(cli, exported, "hidden_lights") > 0.0, "the floor below the mirrored lamp is lit"


def test_a_world_without_nodes_gives_its_colour_as_the_background(exported):
    background = document(exported, "world_without_nodes")["extensions"]["VKDR_background"]
    assert background["radiance"] == pytest.approx([0.3, 0.2, 0.1], rel=1e-6)


def test_a_world_surface_that_is_not_a_background_is_reported(exported):
    assert "VKDR_background" not in document(exported, "world_mix_shader").get("extensions", {})
    assert any("ShaderNodeMixShader" in w and "not a Background" in w
               for w in own_warnings(exported, "world_mix_shader"))


def test_volume_objects_whose_names_clash_as_file_names_get_files_of_their_own(exported):
    doc = document(exported, "same_file_names")
    grids = {m["name"]: m["extensions"]["VKDR_participating_media"]["density"] for m in doc["materials"]
             if "VKDR_participating_media" in m.get("extensions", {})}
    assert sorted(grids) == ["Дым", "Пар"]
    assert grids["Дым"]["uri"] != grids["Пар"]["uri"]
    for entry, source in ((grids["Дым"], "cornell_plume.vdb"), (grids["Пар"], "cornell_fire_flame.vdb")):
        copied = exported / "same_file_names" / entry["uri"]
        assert copied.read_bytes() == (HERE.parents[1] / "scenes" / source).read_bytes()


def test_volume_objects_of_one_file_share_one_copy_of_it(exported, cli):
    doc = document(exported, "shared_grid_file")
    uris = {m["extensions"]["VKDR_participating_media"]["density"]["uri"] for m in doc["materials"]
            if "VKDR_participating_media" in m.get("extensions", {})}
    assert len(uris) == 1 and sorted(p.name for p in (exported / "shared_grid_file").glob("*.vdb")) == sorted(uris)
    assert sum(m["name"].startswith("Cloud") for m in doc["materials"]) == 2
    assert np.isfinite(render_mean(cli, exported, "shared_grid_file"))  # it loads


def test_a_smoke_domain_whose_cache_cannot_be_read_is_exported_empty_with_a_warning(exported, cli):
    doc = document(exported, "smoke_domain")
    domain = next(m for m in doc["materials"] if m["name"] == "Smoke Domain Material")
    medium = domain["extensions"]["VKDR_participating_media"]
    assert medium["sigma_a"] == [0.0] * 3 and medium["sigma_s"] == [0.0] * 3
    assert own_warnings(exported, "smoke_domain") == [
        "smoke domain 'Smoke Domain': its cache format is UNI, not OpenVDB; exported as an empty medium"]
    render_mean(cli, exported, "smoke_domain")


def test_a_baked_smoke_simulation_is_exported_with_its_grids_over_the_domain(exported, cli):
    """The cache of the frame is copied beside the scene and read as the domain's density;
    the simulation's cells (the longest side's resolution, the others from its cell size,
    as Blender sets them) are stretched over the domain's box, as Cycles reads them:
    the first and last cell centres lie half a cell inside the box."""
    assert own_warnings(exported, "baked_smoke") == []
    doc = document(exported, "baked_smoke")
    domain = next(m for m in doc["materials"] if m["name"] == "Smoke Domain Material")
    density = domain["extensions"]["VKDR_participating_media"]["density"]
    assert density["grid"] == "density"
    case = exported / "baked_smoke"
    assert (case / density["uri"]).read_bytes() == (case / "cache" / "data" / "fluid_data_0006.vdb").read_bytes()
    facts = json.loads((case / "baked_smoke.json").read_text())
    voxel, world = np.array(facts["voxel"]), np.array(facts["matrix_world"])
    cell_size = np.linalg.norm(voxel[:3, :3], axis=0)
    resolution = np.maximum((np.array(facts["dimensions"]) / cell_size + 0.5).astype(int), 4)
    z_up_to_y_up = np.array([[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]])
    node = np.array(doc["nodes"][density["node"]]["matrix"]).reshape(4, 4).T
    for index, side in ((np.zeros(3), -1.0), (resolution - 1.0, 1.0)):
        placed = node @ voxel @ np.append(index, 1.0)
        inset = side * (1.0 - 1.0 / resolution)  # the unit cube's face, half a cell in
        assert placed == pytest.approx(z_up_to_y_up @ world @ np.append(inset, 1.0), abs=1e-5)
    # The smoke shows: with its medium emptied the image changes.
    medium = domain["extensions"]["VKDR_participating_media"]
    medium["sigma_a"] = medium["sigma_s"] = [0.0, 0.0, 0.0]
    (case / "clear.gltf").write_text(json.dumps(doc))
    assert render_mean(cli, exported, "baked_smoke") != render_mean(cli, exported, "baked_smoke", "clear.gltf")


def test_glass_is_exported_opaque_with_a_warning_and_loads(exported, cli):
    glass = next(m for m in document(exported, "glass")["materials"] if m["name"] == "Glass")
    assert not set(glass.get("extensions", {})) & {"KHR_materials_transmission", "KHR_materials_ior",
                                                    "KHR_materials_volume"}
    assert any("Transmission is exported as an opaque surface" in w for w in own_warnings(exported, "glass"))
    # A procedural Base Color: its unlinked value, with a warning, not the exporter's white.
    noisy = next(m for m in document(exported, "glass")["materials"] if m["name"] == "Noisy")
    assert noisy["pbrMetallicRoughness"]["baseColorFactor"] == pytest.approx([0.2, 0.4, 0.6, 1.0], rel=1e-6)
    assert any("material 'Noisy'" in w and "input 'Base Color' is linked" in w for w in own_warnings(exported, "glass"))
    render_mean(cli, exported, "glass")


def test_textured_emitters_keep_their_texture_and_what_glTF_cannot_carry_is_reported(exported, cli):
    doc = document(exported, "textured_materials")
    warnings = own_warnings(exported, "textured_materials")
    for name in ("Plain", "Odd"):
        material = next(m for m in doc["materials"] if m["name"] == name)
        assert "emissiveTexture" in material
        assert material["pbrMetallicRoughness"]["metallicFactor"] == 0.0
        # The texture times Strength 2, not times the unlinked red Cycles does not use.
        strength = material["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"]
        assert [strength * c for c in material["emissiveFactor"]] == pytest.approx([2.0, 2.0, 2.0])
    plain = [w for w in warnings if "'Plain'" in w]
    assert plain == []
    odd = [w for w in warnings if w.startswith("material 'Odd': image texture")]
    for expected in ("extension Clip is exported as Extend", "Closest interpolation is exported as Linear",
                     "Box projection is exported as Flat",
                     "colour space 'Non-Color'", "cannot be exported as a texture transform",
                     "output 'Generated', which glTF cannot carry"):
        assert sum(expected in w for w in odd) == 1, (expected, odd)
    render_mean(cli, exported, "textured_materials")


def test_only_light_nodes_that_change_the_light_are_reported(exported):
    warned = [w for w in own_warnings(exported, "light_nodes") if "shader nodes" in w]
    assert len(warned) == 1 and warned[0].startswith("light 'Five'")


def test_new_files_get_the_umasks_permissions(exported):
    for case in ("instanced_lights", "glass"):
        mode = (exported / case / "scene.gltf").stat().st_mode & 0o777
        assert mode == result(exported, case)["new_file_mode"]


def test_objects_in_collections_cycles_does_not_render_are_not_exported(exported):
    names = {node.get("name") for node in document(exported, "hidden_collections")["nodes"]}
    assert not names & {"NestedCube", "NestedBulb", "ExcludedCube", "ExcludedBulb"}, names


def test_an_animated_scene_is_exported_at_the_current_frame(exported):
    moving = next(n for n in document(exported, "animated")["nodes"] if n.get("name") == "Moving")
    assert moving["translation"][0] == pytest.approx(2.0)


def test_a_world_named_like_a_material_gets_a_medium_name_of_its_own(exported, cli):
    doc = document(exported, "world_named_like_a_material")
    assert doc["extensions"]["VKDR_participating_media"]["name"] == "Fog (World)"
    render_mean(cli, exported, "world_named_like_a_material")  # medium names must be unique to load


def test_a_world_named_like_two_materials_gets_a_medium_name_of_its_own(exported, cli):
    doc = document(exported, "world_named_like_two_materials")
    assert doc["extensions"]["VKDR_participating_media"]["name"] == "World (World 2)"
    render_mean(cli, exported, "world_named_like_two_materials")


def test_a_file_of_the_users_is_not_replaced_by_a_texture_and_an_export_replaces_its_own(exported, cli):
    error = result(exported, "users_photo")["error"]
    assert "photo.png" in error and "move it, or export to another folder" in error
    users = exported / "users_folder"
    assert (users / "photo.png").read_text() == "the user's photo"
    assert sorted(p.name for p in users.iterdir()) == ["photo.png"], "nothing written, no staging folder left"
    assert "error" not in result(exported, "exported_once") and "error" not in result(exported, "exported_twice")
    twice = exported / "twice_folder"
    assert sorted(p.name for p in twice.iterdir()) == ["photo.png", "scene.bin", "scene.gltf"]
    photo = vkdiffrender.read_image(str(twice / "photo.png"))  # the second export's, all green
    assert photo[..., 1].min() > photo[..., 0].max()
    render_mean(cli, twice.parent, twice.name)


def test_an_image_whose_file_is_missing_is_reported_and_the_scene_loads(exported, cli):
    assert [w for w in own_warnings(exported, "missing_image")
            if "material 'Gone': image 'gone' is not packed and /nonexistent/gone.png is no file" in w]
    render_mean(cli, exported, "missing_image")


def test_a_muted_volume_node_is_exported_as_cycles_renders_it_no_medium(exported):
    doc = document(exported, "muted_volume")
    muted = next(m for m in doc["materials"] if m["name"] == "Muted")
    assert "VKDR_participating_media" not in muted.get("extensions", {})


def test_a_volume_the_export_cannot_read_leaves_its_boundary_clear_not_opaque(exported, cli):
    doc = document(exported, "muted_volume")
    grouped = next(m for m in doc["materials"] if m["name"] == "Grouped")
    medium = grouped["extensions"]["VKDR_participating_media"]
    assert medium["sigma_a"] == [0.0] * 3 and medium["sigma_s"] == [0.0] * 3
    assert any("material 'Grouped': its volume ('Group') cannot be exported" in w
               for w in own_warnings(exported, "muted_volume"))
    render_mean(cli, exported, "muted_volume")


def test_an_output_for_cycles_alone_wins_over_the_active_one_for_all_renderers(exported):
    materials = {m["name"]: m for m in document(exported, "cycles_output")["materials"]}
    medium = materials["TwoOutputs"]["extensions"]["VKDR_participating_media"]
    # Principled Volume's defaults (Color 0.5, Absorption Color black): sigma_s = 0.5 x density.
    assert medium["sigma_s"] == pytest.approx([0.5] * 3)


def test_a_volume_through_reroutes_is_exported_and_one_through_a_muted_link_is_not(exported):
    materials = {m["name"]: m.get("extensions", {}) for m in document(exported, "rerouted_volumes")["materials"]}
    direct, rerouted = (materials[name]["VKDR_participating_media"] for name in ("Direct", "Rerouted"))
    assert rerouted == direct
    assert "VKDR_participating_media" not in materials["MutedLink"]
    assert not [w for w in own_warnings(exported, "rerouted_volumes") if "Reroute" in w]


def test_an_export_that_fails_leaves_the_previous_one(exported):
    assert "scene.bin" in result(exported, "failing_export")["error"]
    failing = exported / "failing"
    assert (failing / "scene.gltf").read_text() == "the previous export"
    assert (failing / "scene.bin" / "keep").read_text() == "a file of the user's"
    assert sorted(p.name for p in failing.iterdir()) == ["scene.bin", "scene.gltf"], "no staging folder left"


def test_an_emitter_cycles_shows_from_behind_is_double_sided_whatever_its_backface_culling(exported, cli):
    material = next(m for m in document(exported, "backface_culled_emitter")["materials"] if m["name"] == "CulledGlow")
    assert material["doubleSided"] is True
    assert render_mean(cli, exported, "backface_culled_emitter") > 0.0, "the camera sees the panel's back glow"


def test_film_settings_and_pixels_that_change_cycles_image_are_warned_of(exported):
    warnings = own_warnings(exported, "film_and_pixels")
    assert any(w.startswith("Cycles' film Exposure 4 scales its render by 4") for w in warnings), warnings
    assert any(w.startswith("Cycles' film Transparent renders the background") for w in warnings), warnings
    assert any(w.startswith("the render's pixels are not square (Pixel Aspect 2 x 1)") and
               w.endswith("render 160 x 40 for Cycles' view") for w in warnings), warnings


def test_objects_cycles_clips_are_named(exported):
    warnings = own_warnings(exported, "clipped_objects")
    assert [w for w in warnings if "Clip" in w] == [
        "camera 'camera': object 'Near' in view nearer than its Clip Start (1), where Cycles renders nothing and "
        "vkdiffrender renders them: lower Clip Start for Cycles renders that vkdiffrender should match",
        "camera 'camera': objects 'Far', 'Plane' in view beyond its Clip End (6), where Cycles renders nothing and "
        "vkdiffrender renders them: raise Clip End for Cycles renders that vkdiffrender should match"]


def test_an_orthographic_camera_is_exported_with_the_view_cycles_renders(exported, cli):
    camera = document(exported, "orthographic_camera")["cameras"][0]
    assert camera["type"] == "orthographic"
    # Orthographic Scale 3 over the height (Sensor Fit Vertical) of a 2:1 image.
    assert (camera["orthographic"]["xmag"], camera["orthographic"]["ymag"]) == pytest.approx((3.0, 1.5))
    assert np.isfinite(render_mean(cli, exported, "orthographic_camera"))


@pytest.mark.parametrize("case, message", [
    ("panoramic_camera", "camera 'camera': pano cameras are not supported"),
    ("symbolic_link", "link.gltf: is a symbolic link"),
    ("missing_directory", "no such directory: the directory does not exist"),
    ("nan_density", "material 'NanFog': input 'Density' of node 'Principled Volume' is not a finite number"),
    ("open_volume", "object 'Sheet': its faces of material 'OpenFog', a volume, do not close (4 edges"),
    ("nan_light_power", "light 'Bulb': its energy is not a finite number"),
    ("blinding_volume", "materials[0].extensions.VKDR_participating_media.emission ('BlindingFog'): emits 1e+13 in "
                        "its brightest channel, more than the 1e+12 vkdiffrender takes"),
    ("blinding_light", "extensions.KHR_lights_punctual.lights[0] ('Blinding'): emits 7.95775e+28 in its brightest "
                       "channel, more than the 1e+12 vkdiffrender takes"),
    ("glb_path", "scene.glb: the export writes a .gltf with a .bin beside it; give a path ending in .gltf"),
    ("area_light_of_no_size", "light 'Panel': an area light of no area"),
    ("area_emitter_named_like_a_material", "light 'Lamp': its emitter's material would be named 'Lamp.area'"),
    ("bright_colour_attribute", "mesh 'Bright': colour attribute 'Col' holds (0.5, 1.5, 0.5) at element 0; vertex "
                                "colours must be within [0, 1]"),
    # Cycles subtracts negative light; exported as none it would render another image.
    ("negative_lamp", "light 'Drain': its Power (a sun's Strength) is negative (-100); Cycles subtracts such light"),
    ("negative_emission", "material 'Sink': its Emission (Color x Strength) is negative (-2, -2, -2)"),
    ("negative_world", "world 'Dark': its Background (Color x Strength) is negative"),
    ("negative_principled_emission", "material 'Hole': its Emission x Emission Strength is negative (-5, -5, -5)"),
])
def test_what_cannot_be_exported_is_refused_before_anything_is_written(exported, case, message):
    assert message in result(exported, case)["error"]
    assert not (exported / case / "scene.gltf").exists()
    assert (exported / "elsewhere.gltf").read_text() == "the user's file"
    assert not (exported / "no such directory").exists()


def test_faces_without_a_material_get_cycles_default_surface(exported, cli):
    doc = document(exported, "unused_slot")
    floor = doc["meshes"][next(n["mesh"] for n in doc["nodes"] if n.get("name") == "Plane")]
    assert [doc["materials"][p["material"]]["name"] for p in floor["primitives"]] == ["Floor"]
    doc = document(exported, "split_volume_cube")  # its floor has no material
    floor = doc["meshes"][next(n["mesh"] for n in doc["nodes"] if n.get("name") == "Plane")]
    default = doc["materials"][floor["primitives"][0]["material"]]
    assert default["name"] == "default surface"
    assert default["pbrMetallicRoughness"] == {"baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0,
                                               "roughnessFactor": 1.0}
    render_mean(cli, exported, "split_volume_cube")  # it loads


def test_a_volume_whose_faces_are_split_apart_is_closed_as_the_loader_counts_it(exported, cli):
    assert "error" not in result(exported, "split_volume_cube")
    doc = document(exported, "split_volume_cube")
    assert "VKDR_participating_media" in next(m for m in doc["materials"] if m["name"] == "SplitFog")["extensions"]


def test_what_blenders_exporter_leaves_out_is_warned_of_and_not_offered_for_a_fit(exported):
    warnings = own_warnings(exported, "unexported_geometry")
    assert any(w.startswith("object 'Blob': a metaball, which Blender's glTF exporter leaves out") for w in warnings)
    assert any(w.startswith("object 'Scatter': its Geometry Nodes make 3 instances") for w in warnings)
    assert not any(w.startswith(("object 'Label'", "object 'Painted'")) for w in warnings)  # text; a tree that paints
    assert any(w.startswith("light 'Shadowless': its ray visibility and Cast Shadow are not exported")
               for w in warnings)
    fittable = result(exported, "unexported_geometry")["fittable"]
    assert not any("BlobFog" in name for name in fittable)
    # The exporter writes a face with its object's slot's material, whatever a node tree set.
    assert "materials/Painted/base_color" in fittable and "materials/FromNodes/base_color" not in fittable
    assert "Painted" in [m["name"] for m in document(exported, "unexported_geometry")["materials"]]
    # A material in a slot no face uses is in no exported mesh, and a camera the exporter
    # leaves out (panoramic) or the render hides gets no target.
    assert result(exported, "unused_slot")["fittable"] == ["materials/Floor/base_color"]
    assert result(exported, "unused_slot")["cameras"] == ["camera"]
    assert not any("cameras;" in w for w in own_warnings(exported, "unused_slot"))


def test_a_scene_name_with_a_percent_sign_refers_to_its_own_buffer(exported, cli):
    doc = json.loads((exported / "percent_name" / "a%20b.gltf").read_text())
    assert doc["buffers"][0]["uri"] == "a%2520b.bin"
    assert render_mean(cli, exported / "percent_name", ".", "a%20b.gltf") > 0.0


def test_alpha_below_one_and_a_base_color_of_nodes_are_warned_of(exported):
    warnings = own_warnings(exported, "see_through")
    assert any(w.startswith("material 'Veil': Alpha below 1 is exported as an opaque surface") for w in warnings)
    assert any(w.startswith("material 'Veil': 'Principled BSDF' input 'Base Color' is linked from 'Noise "
                            "Texture' (ShaderNodeTexNoise)") for w in warnings)
