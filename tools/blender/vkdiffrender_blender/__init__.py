"""Blender add-on: export a scene with its volumes and lights for vkdiffrender, fit its
parameters to target images with `vkdiffrender optimize`, and import fitted scenes back
into Cycles' nodes (docs/blender.md). The Blender modules are imported in register(), so
that mappings.py can be imported and tested without Blender."""

bl_info = {
    "name": "vkdiffrender",
    "author": "vkdiffrender",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "File > Export / Import > vkdiffrender; Properties > Render > vkdiffrender Fit",
    "description": "Export volumes and lights for vkdiffrender, fit them to images, write the fit back",
    "category": "Import-Export",
}


def classes():
    from . import export_scene, fit, import_scene
    return (export_scene.EXPORT_OT_vkdiffrender, import_scene.IMPORT_OT_vkdiffrender) + fit.CLASSES


def register():
    import bpy
    from . import export_scene, fit, import_scene
    for cls in classes():
        bpy.utils.register_class(cls)
    bpy.types.TOPBAR_MT_file_export.append(export_scene.menu_entry)
    bpy.types.TOPBAR_MT_file_import.append(import_scene.menu_entry)
    fit.register_properties()


def unregister():
    import bpy
    from . import export_scene, fit, import_scene
    fit.unregister_properties()
    bpy.types.TOPBAR_MT_file_import.remove(import_scene.menu_entry)
    bpy.types.TOPBAR_MT_file_export.remove(export_scene.menu_entry)
    for cls in reversed(classes()):
        bpy.utils.unregister_class(cls)
