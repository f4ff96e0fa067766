"""Compare Renders: a dialog (folder, preview size, samples), then BXDF_LAB, CYCLES and POVRAY_RENDER
render the scene one after the other as Blender render jobs (the UI stays live; the status bar
shows which engine runs; Esc stops), and the labelled result opens in an Image Editor with the
HTML report one click away ("Open Comparison Report")."""

import os

import bpy
from bpy.props import IntProperty, StringProperty

from .. import bake_figure, compare

TIMER_INTERVAL = 0.2


class BXDFLAB_OT_compare_renders(bpy.types.Operator):
    """Render the scene with BxDF Lab, Cycles and POV-Ray at a preview size and show the images side by side with their differences"""
    bl_idname = "bxdf_lab.compare_renders"
    bl_label = "Compare Renders"

    directory: StringProperty(name="Output Folder", subtype="DIR_PATH", default="",
                              description="Where the renders (EXR), the figure and the HTML report go")
    size: IntProperty(name="Preview Size", default=256, min=16, max=8192, subtype="PIXEL",
                      description="Longest side of the renders (the scene's resolution is scaled down)")
    samples: IntProperty(name="Samples", default=32, min=1, max=1 << 16,
                         description="Samples per pixel of BxDF Lab and Cycles")

    def invoke(self, context, _event):
        if not self.directory and bpy.data.filepath:
            self.directory = "//bxdf_compare/"
        return context.window_manager.invoke_props_dialog(self, width=420)

    def draw(self, _context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(self, "directory")
        layout.prop(self, "size")
        layout.prop(self, "samples")
        if not self.directory:
            layout.label(text="Choose a folder (the file is not saved yet)", icon="ERROR")

    def _options(self):
        if not self.directory:
            self.report({"ERROR"}, "Compare Renders: choose an output folder")
            return None
        return compare.Options(folder=self.directory, size=self.size, samples=self.samples)

    # ---- headless (and scripts): every engine in turn, blocking ---------------------------

    def execute(self, context):
        options = self._options()
        if options is None:
            return {"CANCELLED"}
        if context.window is not None and not bpy.app.background:
            return self._start_modal(context, options)
        run = compare.CompareRun(context.scene, options)
        try:
            for engine_id in compare.ENGINES:
                run.render_blocking(engine_id)
        finally:
            run.abort()
        return self._finish(context, run)

    # ---- with a window: render jobs driven from a modal loop ------------------------------

    def _start_modal(self, context, options):
        self.run = compare.CompareRun(context.scene, options)
        self.windows_before = {w.as_pointer() for w in context.window_manager.windows}
        self.done = None  # set by the render handlers: "complete" or "cancel"; "all" once every engine ran
        bpy.app.handlers.render_complete.append(self._on_complete)
        bpy.app.handlers.render_cancel.append(self._on_cancel)
        self.timer = context.window_manager.event_timer_add(TIMER_INTERVAL, window=context.window)
        context.window_manager.modal_handler_add(self)
        if not self._next(context):
            return self._end(context, finished=True)
        return {"RUNNING_MODAL"}

    def _on_complete(self, *_):
        self.done = "complete"

    def _on_cancel(self, *_):
        self.done = "cancel"

    def _next(self, context):
        """Starts the next engine's render job; False when none is left."""
        while self.run.pending:
            engine_id = self.run.pending.pop(0)
            if not self.run.begin(engine_id):
                continue
            self.done = None
            done = len(self.run.results)
            context.workspace.status_text_set(
                f"Compare Renders: {compare.ENGINE_NAMES[engine_id]} ({done} of "
                f"{len(compare.ENGINES)}), {self.size} px, {self.samples} samples — Esc to stop")
            started = bpy.ops.render.render("INVOKE_DEFAULT", write_still=True)
            if "RUNNING_MODAL" in started:
                return True
            self.run.end(f"Blender did not start the render job ({', '.join(sorted(started))}); "
                         "is another render running?")
        return False

    def modal(self, context, event):
        if event.type == "ESC":
            return self._end(context, finished=False)
        # render_complete runs on the job's thread before the job ends, and render.render
        # refuses to start while a render job exists: wait for the job itself to end. Each step
        # also switches the engine and the materials' use_nodes under any material preview that
        # the last step's settings started (a Cycles preview registering its passes on its
        # thread while POV-Ray's job started crashed Blender), and ending disables the add-ons
        # the run enabled, which re-registers RNA types under it ("'ID' object has no attribute
        # 'camera'", then a crash): wait for previews too.
        if (event.type != "TIMER" or self.done is None or bpy.app.is_job_running("RENDER")
                or bpy.app.is_job_running("RENDER_PREVIEW")):
            return {"PASS_THROUGH"}
        if self.done == "all":
            return self._end(context, finished=True)
        if self.done == "cancel":  # Esc in the render job
            self.run.end("cancelled")
            return self._end(context, finished=False)
        self.run.end()
        if self._next(context):
            return {"PASS_THROUGH"}
        self.done = "all"  # the last step's restored settings may start a preview: next tick
        return {"PASS_THROUGH"}

    def _end(self, context, finished):
        context.window_manager.event_timer_remove(self.timer)
        for handlers, fn in ((bpy.app.handlers.render_complete, self._on_complete),
                             (bpy.app.handlers.render_cancel, self._on_cancel)):
            if fn in handlers:
                handlers.remove(fn)
        context.workspace.status_text_set(None)
        self.run.abort()
        if not finished:
            self.report({"WARNING"}, "Compare Renders stopped; the scene's settings are restored")
            return {"CANCELLED"}
        return self._finish(context, self.run, self._render_windows(context))

    def _render_windows(self, context):
        """The windows the run's render jobs opened (Blender's Render window, by default)."""
        return [w for w in context.window_manager.windows if w.as_pointer() not in self.windows_before]

    # ---- the result -----------------------------------------------------------------------

    def _finish(self, context, run, render_windows=()):
        for result in run.results:
            if not result.ok:
                self.report({"WARNING"}, f"{compare.ENGINE_NAMES[result.engine]}: {result.message}")
        image = run.finish()
        if image is None:
            self.report({"ERROR"}, "Compare Renders: no engine rendered")
            return {"CANCELLED"}
        # The Render window the jobs opened would sit over the figure showing the last engine's
        # render: the figure goes into the user's own Image Editor and that window closes; with no
        # Image Editor of their own, the Render window shows the figure.
        own = [w for w in context.window_manager.windows if w not in render_windows]
        if bake_figure.show_in_image_editor(context, image, own):
            for window in render_windows:
                with context.temp_override(window=window):
                    bpy.ops.wm.window_close()
        else:
            bake_figure.show_in_image_editor(context, image, render_windows)
        self.report({"INFO"}, f"Comparison in '{image.name}'; report: {compare.last_result['report']}")
        return {"FINISHED"}


class BXDFLAB_OT_open_compare_report(bpy.types.Operator):
    """Open the last Compare Renders report (HTML) in the web browser"""
    bl_idname = "bxdf_lab.open_compare_report"
    bl_label = "Open Comparison Report"

    @classmethod
    def poll(cls, _context):
        return os.path.exists(compare.last_result.get("report", ""))

    def execute(self, _context):
        bpy.ops.wm.url_open(url="file://" + compare.last_result["report"])
        return {"FINISHED"}


classes = (BXDFLAB_OT_compare_renders, BXDFLAB_OT_open_compare_report)
