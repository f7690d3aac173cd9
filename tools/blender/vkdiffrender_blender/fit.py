"""The Fit panel (Properties > Render > vkdiffrender Fit): choose parameters and a target
image per camera, run `vkdiffrender optimize` as a subprocess with progress and loss in
the status bar (Esc stops it, keeping its checkpoint), and write the fitted values back.
The run itself (command, progress, cancel, write-back) is fit_run.py, which has no bpy;
this file is the panel, the settings and the modal operator's event handling."""
import os

import bpy
from bpy.props import BoolProperty, CollectionProperty, FloatProperty, IntProperty, PointerProperty, StringProperty

from . import export_scene, fit_run, write_back


class VKDR_Preferences(bpy.types.AddonPreferences):
    bl_idname = __package__
    cli_path: StringProperty(name="vkdiffrender binary", default="vkdiffrender", subtype="FILE_PATH",
                             description="The vkdiffrender command line (a name on PATH or a path)")

    def draw(self, context):
        self.layout.prop(self, "cli_path")


class VKDR_FitParameter(bpy.types.PropertyGroup):
    name: StringProperty()
    enabled: BoolProperty(name="Fit", default=False)


class VKDR_FitTarget(bpy.types.PropertyGroup):
    name: StringProperty()  # the camera object's name
    image: StringProperty(name="Target", subtype="FILE_PATH", description="Linear EXR (or PNG) this camera should see")


class VKDR_FitSettings(bpy.types.PropertyGroup):
    parameters: CollectionProperty(type=VKDR_FitParameter)
    targets: CollectionProperty(type=VKDR_FitTarget)
    iterations: IntProperty(name="Iterations", default=100, min=1)
    spp: IntProperty(name="Samples per pixel", default=16, min=1)
    learning_rate: FloatProperty(name="Learning rate", default=0.05, min=1e-6, description="Relative step (log units)")
    run_directory: StringProperty(name="Run directory", default="//vkdiffrender_fit", subtype="DIR_PATH")


def cli_path(context):
    addon = context.preferences.addons.get(__package__)
    return addon.preferences.cli_path if addon else "vkdiffrender"


def fit_request(context, scene_file):
    """The panel's settings as a fit_run.FitRequest, paths made absolute."""
    settings = context.scene.vkdr_fit
    return fit_run.FitRequest(
        cli=cli_path(context), scene_file=scene_file,
        targets={t.name: bpy.path.abspath(t.image) for t in settings.targets if t.image},
        parameters=tuple(p.name for p in settings.parameters if p.enabled),
        iterations=settings.iterations, spp=settings.spp, learning_rate=settings.learning_rate,
        max_depth=context.scene.cycles.max_bounces + 1, run_directory=bpy.path.abspath(settings.run_directory))


class VKDR_OT_fit_refresh(bpy.types.Operator):
    """List the scene's fittable parameters and its cameras"""
    bl_idname = "vkdiffrender.fit_refresh"
    bl_label = "Refresh parameters"

    def execute(self, context):
        settings = context.scene.vkdr_fit
        chosen = {p.name for p in settings.parameters if p.enabled}
        images = {t.name: t.image for t in settings.targets}
        settings.parameters.clear()
        for name in write_back.fittable_parameters(context.scene, context.view_layer):
            entry = settings.parameters.add()
            entry.name, entry.enabled = name, name in chosen
        settings.targets.clear()
        exported = set(export_scene.exported_cameras(context.scene, context.view_layer))
        for obj in context.scene.objects:
            if obj in exported:
                entry = settings.targets.add()
                entry.name, entry.image = obj.name, images.get(obj.name, "")
        return {"FINISHED"}


class VKDR_OT_fit(bpy.types.Operator):
    """Fit the checked parameters to the target images with vkdiffrender optimize (Esc cancels)"""
    bl_idname = "vkdiffrender.fit"
    bl_label = "Fit with vkdiffrender"

    @classmethod
    def poll(cls, context):
        settings = context.scene.vkdr_fit
        return any(p.enabled for p in settings.parameters) and any(t.image for t in settings.targets)

    def invoke(self, context, event):
        run_directory = context.scene.vkdr_fit.run_directory
        if run_directory.startswith("//") and not bpy.data.filepath:
            self.report({"ERROR"}, f"the run directory {run_directory} is relative to the .blend file, which has not "
                                   f"been saved: save it, or choose an absolute run directory")
            return {"CANCELLED"}
        run_directory = bpy.path.abspath(run_directory)
        scene_file = os.path.join(run_directory, "exported.gltf")
        try:
            os.makedirs(run_directory, exist_ok=True)
            warnings = export_scene.export_scene(context, scene_file)
        except (export_scene.ExportError, OSError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        except Exception as error:  # as the export operator reports it
            self.report({"ERROR"}, f"the export failed on what it does not handle ({type(error).__name__}: {error})")
            return {"CANCELLED"}
        for warning in warnings:
            self.report({"WARNING"}, warning)
        request = fit_request(context, scene_file)
        try:
            self.run = fit_run.FitRun(request)
        except OSError as error:
            self.report({"ERROR"}, f"cannot run {request.cli}: {error} (set the binary in the add-on's preferences)")
            return {"CANCELLED"}
        # The fitted values go to the scene and view layer exported, whichever the user
        # turns to while the run goes on.
        self.scene_name, self.view_layer_name = context.scene.name, context.view_layer.name
        self.timer = context.window_manager.event_timer_add(0.5, window=context.window)
        context.window_manager.modal_handler_add(self)
        context.window_manager.progress_begin(0, request.iterations)
        return {"RUNNING_MODAL"}

    def finish(self, context):
        context.window_manager.event_timer_remove(self.timer)
        context.window_manager.progress_end()
        context.workspace.status_text_set(None)

    def modal(self, context, event):
        if event.type == "ESC":
            # optimize ends once its current pass has (poll() says when), checkpointed.
            self.run.request_cancel()
            context.workspace.status_text_set("vkdiffrender fit: cancelling after the current pass")
            return {"RUNNING_MODAL"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        if self.run.cancelled:
            if self.run.poll() is None:
                return {"RUNNING_MODAL"}
            self.finish(context)
            self.report({"WARNING"}, f"fit cancelled; {self.run.resume_hint()}")
            return {"CANCELLED"}
        done, loss = self.run.progress()
        context.window_manager.progress_update(done)
        context.workspace.status_text_set(fit_run.status_text(done, self.run.request.iterations, loss))
        if self.run.poll() is None:
            return {"RUNNING_MODAL"}
        self.finish(context)
        if not self.run.succeeded:
            self.report({"ERROR"}, self.run.failure_message())
            return {"CANCELLED"}
        scene = bpy.data.scenes.get(self.scene_name)
        view_layer = scene.view_layers.get(self.view_layer_name) if scene is not None else None
        if view_layer is None:
            self.report({"ERROR"}, f"scene '{self.scene_name}' or its view layer '{self.view_layer_name}', which the "
                                   f"fit exported, is gone: the fitted values are in {self.run.params_path}")
            return {"CANCELLED"}
        for warning in self.run.write_back(lambda params: write_back.apply_fitted_values(scene, view_layer, params)):
            self.report({"WARNING"}, warning)
        self.report({"INFO"}, f"fitted values written back (loss {loss:.4g})" if loss is not None else "fitted")
        return {"FINISHED"}


class VKDR_PT_fit(bpy.types.Panel):
    bl_label = "vkdiffrender Fit"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"

    def draw(self, context):
        settings = context.scene.vkdr_fit
        layout = self.layout
        layout.operator(VKDR_OT_fit_refresh.bl_idname, icon="FILE_REFRESH")
        box = layout.box()
        box.label(text="Parameters")
        for parameter in settings.parameters:
            box.prop(parameter, "enabled", text=parameter.name)
        box = layout.box()
        box.label(text="Target image per camera")
        for target in settings.targets:
            box.prop(target, "image", text=target.name)
        layout.prop(settings, "iterations")
        layout.prop(settings, "spp")
        layout.prop(settings, "learning_rate")
        layout.prop(settings, "run_directory")
        layout.operator(VKDR_OT_fit.bl_idname, icon="PLAY")


CLASSES = (VKDR_Preferences, VKDR_FitParameter, VKDR_FitTarget, VKDR_FitSettings, VKDR_OT_fit_refresh,
           VKDR_OT_fit, VKDR_PT_fit)


def register_properties():
    bpy.types.Scene.vkdr_fit = PointerProperty(type=VKDR_FitSettings)


def unregister_properties():
    del bpy.types.Scene.vkdr_fit
