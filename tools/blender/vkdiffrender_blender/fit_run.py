"""One `vkdiffrender optimize` run as the Fit operator drives it, without bpy: the command
line, the subprocess with its console output in a log file, progress read from the run's
log.jsonl, cancelling with SIGINT (optimize then keeps checkpoint.json and exits 130)
and, on success, the fitted values handed to a write-back function. fit.py is the thin
Blender layer over this (timer, status bar, Esc); tests/blender/test_fit_run.py drives
it with the real command line."""
import json
import os
import shlex
import signal
import subprocess
from dataclasses import dataclass

CANCELLED_BY_SIGINT = 130


@dataclass(frozen=True)
class FitRequest:
    """What the Fit panel asks for; paths absolute."""
    cli: str
    scene_file: str
    targets: dict            # camera name -> target image path
    parameters: tuple        # parameter names to fit
    iterations: int
    spp: int
    learning_rate: float
    max_depth: int
    run_directory: str       # the run's console log goes here; optimize's outputs to run_directory/run


def optimize_command(request):
    """The optimize command line. Every parameter but g is stepped in log units, so that
    one learning rate suits coefficients of any scale; g may be negative."""
    command = [request.cli, "optimize", request.scene_file, "--iters", str(request.iterations),
               "--spp", str(request.spp), "--lr", f"{request.learning_rate:.6g}", "--max-depth", str(request.max_depth),
               "--out", output_directory(request), "--overwrite", "--checkpoint-every", "10"]
    for camera, image in request.targets.items():
        command += ["--target", f"{camera}={image}"]
    for name in request.parameters:
        command += ["--param", name]
        if not name.endswith("/g"):
            command += ["--log-param", name]
    return command


def output_directory(request):
    return os.path.join(request.run_directory, "run")


def read_progress(log_path):
    """(iterations done, the last iteration's loss or None) from a log.jsonl, which
    optimize rewrites whole after every iteration; (0, None) before the first."""
    try:
        with open(log_path, encoding="utf-8") as f:
            lines = [line for line in f.read().splitlines() if line.strip()]
    except OSError:
        return 0, None
    if not lines:
        return 0, None
    try:
        loss = json.loads(lines[-1])["loss"]
    except (ValueError, KeyError, TypeError):
        loss = None
    return len(lines), loss


def status_text(done, iterations, loss):
    loss_text = f", loss {loss:.4g}" if loss is not None else ""
    return f"vkdiffrender fit: iteration {done}/{iterations}{loss_text}  (Esc to cancel)"


class FitRun:
    """A started optimize process. poll() while it runs; then succeeded, cancelled or
    failure_message() say how it ended."""

    def __init__(self, request):
        self.request = request
        self.command = optimize_command(request)
        self.out_dir = output_directory(request)
        self.console_path = os.path.join(request.run_directory, "optimize.log")
        os.makedirs(request.run_directory, exist_ok=True)
        with open(self.console_path, "w", encoding="utf-8") as console:
            # The child holds its own copy of the descriptor; ours can close at once.
            self.process = subprocess.Popen(self.command, stdout=console, stderr=subprocess.STDOUT)
        self.cancelled = False

    def progress(self):
        return read_progress(os.path.join(self.out_dir, "log.jsonl"))

    def poll(self):
        """None while running, else the exit code."""
        return self.process.poll()

    def request_cancel(self):
        """Stop the run as Ctrl-C would: optimize finishes its current iteration's pass,
        writes checkpoint.json and exits 130, which poll() then returns. Returns at once: a
        pass may take minutes on a CPU, and Blender's window must stay responsive."""
        if not self.cancelled:
            self.cancelled = True
            self.process.send_signal(signal.SIGINT)

    def cancel(self):
        """request_cancel, then waits for the run to end; returns the exit code."""
        self.request_cancel()
        return self.process.wait()

    @property
    def succeeded(self):
        return not self.cancelled and self.process.returncode == 0

    @property
    def checkpoint_path(self):
        return os.path.join(self.out_dir, "checkpoint.json")

    @property
    def params_path(self):
        return os.path.join(self.out_dir, "params.json")

    def resume_command(self):
        """The command that continues a cancelled run from its checkpoint: the same one
        with --resume in place of --out and --overwrite."""
        command, skip = [], 0
        for argument in self.command:
            if skip:
                skip -= 1
            elif argument == "--out":
                skip = 1
            elif argument != "--overwrite":
                command.append(argument)
        return command + ["--resume", self.out_dir]

    def resume_hint(self):
        return f"continue it with: {shlex.join(self.resume_command())}"

    def failure_message(self):
        """The last line optimize printed (its error), for a run that failed."""
        try:
            with open(self.console_path, encoding="utf-8") as f:
                lines = [line for line in f.read().splitlines() if line.strip()]
        except OSError:
            lines = []
        last = lines[-1] if lines else "no output"
        return f"vkdiffrender optimize failed (exit code {self.process.returncode}): {last}"

    def write_back(self, apply_params):
        """On success, APPLY_PARAMS({name: [values]}) with params.json's values; returns
        what it returns (the write-back's warnings)."""
        if not self.succeeded:
            raise RuntimeError("the run did not succeed; there are no fitted values to write back")
        with open(self.params_path, encoding="utf-8") as f:
            return apply_params(json.load(f))
