"""The Fit operator's logic without Blender (fit_run.py) driving the real command line on
scenes/cornell_fog.gltf at 16 x 16 pixels: progress read from log.jsonl while it runs, a
cancel half way (SIGINT: exit 130, checkpoint.json kept, no fitted values, nothing
written back) that the resume command continues to the end, a run to success whose
params.json is handed to the write-back, and a failing run's message."""
import json
import pathlib
import subprocess
import time

import pytest

from vkdiffrender_blender import fit_run

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
SCENE = REPOSITORY / "scenes" / "cornell_fog.gltf"
POLL_SECONDS = 0.05
TIMEOUT_SECONDS = 120


@pytest.fixture(scope="module")
def target(cli, tmp_path_factory):
    path = tmp_path_factory.mktemp("fit_target") / "target.exr"
    subprocess.run([cli, "render", str(SCENE), "-o", str(path), "--width", "16", "--height", "16", "--spp", "4",
                    "--max-depth", "2", "--set", "media/fog/sigma_a=0.1"],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return str(path)


def request(cli, target, run_directory, iterations, parameter="media/fog/sigma_a"):
    return fit_run.FitRequest(cli=cli, scene_file=str(SCENE), targets={"camera": target}, parameters=(parameter,),
                              iterations=iterations, spp=1, learning_rate=0.05, max_depth=2,
                              run_directory=str(run_directory))


def wait(run, until):
    """Poll as the operator's timer does until UNTIL(done, loss) or the run ends."""
    deadline = time.monotonic() + TIMEOUT_SECONDS
    seen = []
    while run.poll() is None and time.monotonic() < deadline:
        done, loss = run.progress()
        seen.append(done)
        if until(done, loss):
            break
        time.sleep(POLL_SECONDS)
    return seen


def test_command_steps_coefficients_in_log_units_and_g_directly():
    fit = fit_run.FitRequest(cli="vkdr", scene_file="/s.gltf", targets={"cam": "/t.exr"},
                             parameters=("media/fog/sigma_a", "media/fog/g"), iterations=7, spp=3,
                             learning_rate=0.05, max_depth=4, run_directory="/runs/a")
    command = fit_run.optimize_command(fit)
    assert command[:3] == ["vkdr", "optimize", "/s.gltf"]
    text = " ".join(command)
    for expected in ("--iters 7", "--spp 3", "--lr 0.05", "--max-depth 4", "--out /runs/a/run",
                     "--target cam=/t.exr", "--param media/fog/sigma_a --log-param media/fog/sigma_a",
                     "--param media/fog/g"):
        assert expected in text
    assert "--log-param media/fog/g" not in text


def test_progress_of_missing_empty_and_partial_logs(tmp_path):
    log = tmp_path / "log.jsonl"
    assert fit_run.read_progress(str(log)) == (0, None)
    log.write_text("")
    assert fit_run.read_progress(str(log)) == (0, None)
    log.write_text('{"iteration": 0, "loss": 0.5}\n{"iteration": 1, "loss": 0.25}\n')
    assert fit_run.read_progress(str(log)) == (2, 0.25)
    log.write_text('{"iteration": 0, "loss": 0.5}\n{"iteration": 1, "lo')
    assert fit_run.read_progress(str(log)) == (2, None)
    assert fit_run.status_text(2, 10, 0.25) == "vkdiffrender fit: iteration 2/10, loss 0.25  (Esc to cancel)"


def test_cancel_half_way_keeps_the_checkpoint_and_resumes(cli, target, tmp_path):
    iterations = 100
    run = fit_run.FitRun(request(cli, target, tmp_path, iterations))
    seen = wait(run, lambda done, loss: done >= 5)
    assert run.poll() is None, f"the run ended before the cancel (progress seen: {seen})"
    assert run.cancel() == fit_run.CANCELLED_BY_SIGINT
    assert not run.succeeded
    checkpoint = json.loads(pathlib.Path(run.checkpoint_path).read_text())
    done, _ = run.progress()
    assert 5 <= done < iterations
    assert not pathlib.Path(run.params_path).exists(), "a cancelled run wrote fitted values"
    with pytest.raises(RuntimeError):
        run.write_back(lambda params: pytest.fail("a cancelled run was written back"))
    assert checkpoint["iteration"] == done, "the checkpoint is not of the last logged iteration"

    resumed = subprocess.run(run.resume_command(), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    assert resumed.returncode == 0, resumed.stderr
    assert run.progress()[0] == iterations
    assert pathlib.Path(run.params_path).is_file()


def test_success_hands_params_to_the_write_back(cli, target, tmp_path):
    iterations = 3
    run = fit_run.FitRun(request(cli, target, tmp_path, iterations))
    wait(run, lambda done, loss: False)
    assert run.poll() == 0, run.failure_message()
    assert run.succeeded
    done, loss = run.progress()
    assert done == iterations and loss is not None
    written = {}
    assert run.write_back(lambda params: written.update(params) or ["a warning"]) == ["a warning"]
    assert written == json.loads(pathlib.Path(run.params_path).read_text())
    assert list(written) == ["media/fog/sigma_a"]


def test_failure_message_names_the_error(cli, target, tmp_path):
    run = fit_run.FitRun(request(cli, target, tmp_path, 3, parameter="media/nothing/sigma_a"))
    wait(run, lambda done, loss: False)
    assert run.poll() == 2
    assert not run.succeeded
    message = run.failure_message()
    assert "exit code 2" in message and "media/nothing/sigma_a" in message


def test_missing_binary_raises_oserror(target, tmp_path):
    with pytest.raises(OSError):
        fit_run.FitRun(request(str(tmp_path / "no-such-vkdiffrender"), target, tmp_path, 3))
