"""The Fit panel (Properties > Render > vkdiffrender Fit): choose parameters and a target
image per camera, run `vkdiffrender optimize` as a subprocess with progress and loss in
the status bar (Esc stops it, keeping its checkpoint), and write the fitted values back."""
import json
import os
import signal
import subprocess

import bpy
from bpy.props import BoolProperty, CollectionProperty, FloatProperty, IntProperty, PointerProperty, StringProperty

from . import export_scene, write_back


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


def optimize_command(cli, scene_file, settings, max_depth, out_dir):
    """The optimize command line: every positive parameter is stepped in log units, so
    that one learning rate suits coefficients of any scale."""
    command = [cli, "optimize", scene_file, "--iters", str(settings.iterations), "--spp", str(settings.spp),
               "--lr", repr(settings.learning_rate), "--max-depth", str(max_depth), "--out", out_dir,
               "--overwrite", "--checkpoint-every", "10"]
    for target in settings.targets:
        if target.image:
            command += ["--target", f"{target.name}={bpy.path.abspath(target.image)}"]
    for parameter in settings.parameters:
        if parameter.enabled:
            command += ["--param", parameter.name]
            if not parameter.name.endswith("/g"):
                command += ["--log-param", parameter.name]
    return command


class VKDR_OT_fit_refresh(bpy.types.Operator):
    """List the scene's fittable parameters and its cameras"""
    bl_idname = "vkdiffrender.fit_refresh"
    bl_label = "Refresh parameters"

    def execute(self, context):
        settings = context.scene.vkdr_fit
        chosen = {p.name for p in settings.parameters if p.enabled}
        images = {t.name: t.image for t in settings.targets}
        settings.parameters.clear()
        for name in write_back.fittable_parameters(context.scene):
            entry = settings.parameters.add()
            entry.name, entry.enabled = name, name in chosen
        settings.targets.clear()
        for obj in context.scene.objects:
            if obj.type == "CAMERA":
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
        settings = context.scene.vkdr_fit
        self.run_dir = bpy.path.abspath(settings.run_directory)
        os.makedirs(self.run_dir, exist_ok=True)
        scene_file = os.path.join(self.run_dir, "exported.gltf")
        for warning in export_scene.export_scene(context, scene_file):
            self.report({"WARNING"}, warning)
        self.out_dir = os.path.join(self.run_dir, "run")
        command = optimize_command(cli_path(context), scene_file, settings,
                                   context.scene.cycles.max_bounces + 1, self.out_dir)
        self.console = open(os.path.join(self.run_dir, "optimize.log"), "w", encoding="utf-8")
        try:
            self.process = subprocess.Popen(command, stdout=self.console, stderr=subprocess.STDOUT)
        except OSError as error:
            self.console.close()
            self.report({"ERROR"}, f"cannot run {command[0]}: {error} (set the binary in the add-on's preferences)")
            return {"CANCELLED"}
        self.iterations = settings.iterations
        self.timer = context.window_manager.event_timer_add(0.5, window=context.window)
        context.window_manager.modal_handler_add(self)
        context.window_manager.progress_begin(0, self.iterations)
        return {"RUNNING_MODAL"}

    def progress(self):
        """(iterations done, last loss) from the run's log.jsonl, rewritten every iteration."""
        try:
            with open(os.path.join(self.out_dir, "log.jsonl"), encoding="utf-8") as f:
                lines = [line for line in f.read().splitlines() if line.strip()]
        except OSError:
            return 0, None
        try:
            return len(lines), json.loads(lines[-1])["loss"] if lines else None
        except (ValueError, KeyError):
            return len(lines), None

    def finish(self, context):
        context.window_manager.event_timer_remove(self.timer)
        context.window_manager.progress_end()
        context.workspace.status_text_set(None)
        self.console.close()

    def modal(self, context, event):
        if event.type == "ESC":
            self.process.send_signal(signal.SIGINT)  # optimize keeps a checkpoint and exits 130
            self.process.wait()
            self.finish(context)
            self.report({"WARNING"}, f"fit cancelled; continue it with --resume {self.out_dir}")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        done, loss = self.progress()
        context.window_manager.progress_update(done)
        loss_text = f", loss {loss:.4g}" if loss is not None else ""
        context.workspace.status_text_set(f"vkdiffrender fit: iteration {done}/{self.iterations}{loss_text}"
                                          f"  (Esc to cancel)")
        if self.process.poll() is None:
            return {"RUNNING_MODAL"}
        self.finish(context)
        if self.process.returncode != 0:
            with open(os.path.join(self.run_dir, "optimize.log"), encoding="utf-8") as f:
                last = [line for line in f.read().splitlines() if line.strip()][-1:]
            self.report({"ERROR"}, f"vkdiffrender optimize failed: {' '.join(last)}")
            return {"CANCELLED"}
        for warning in write_back.apply_params_file(context.scene, os.path.join(self.out_dir, "params.json")):
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
