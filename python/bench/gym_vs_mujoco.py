"""Environment steps per second of ARS's ``ars/ConicalPendulum-v0`` beside MuJoCo's
``InvertedPendulum-v5`` (issue 22), single environment and vector environments of
N = 1, 2, 4, 8, printed side by side; then ARS's make_vec N = 2 against its single
environment, and where the vector step's time goes (Python against native stepping).

- Single: ``gymnasium.make(id)`` with Gymnasium's default wrappers (the same for both).
- ARS vector: ``ars.gym.make_vec`` (what ``gymnasium.make_vec`` gives for ``ars/``
  ids): the actions applied in Python, the N simulations stepped by one
  ``ars.step_many`` call on native threads.
- MuJoCo vector: ``gymnasium.make_vec(..., vectorization_mode="sync")`` (one process,
  one environment after the other) and ``"async"`` (one worker process per
  environment, Gymnasium's ``AsyncVectorEnv``).

Actions are drawn beforehand from the seeded action space (sampling is not timed);
each configuration runs for ``--seconds`` of wall time after a warm-up, ``--repeats``
times in turn with the others, and its best round among those in which other programs
kept at most 0.15 cores busy is kept (marked "busy machine" when there was none). An environment
step is 80 ODE steps (0.02 s simulated) for ARS's pendulum and 2 MuJoCo steps
(0.04 s) for MuJoCo's: the table also gives physics steps per second.

Needs both ARS and ``gymnasium[mujoco]`` in one environment, kept apart from the test
environment (``.venv``):

    python3 -m venv .venv-bench
    .venv-bench/bin/pip install "gymnasium[mujoco]>=1.0" numpy
    .venv-bench/bin/pip install ./python
    .venv-bench/bin/python python/bench/gym_vs_mujoco.py
"""

import argparse
import os
import platform
import time

import gymnasium

import ars
import ars.gym

ARS_ID, MUJOCO_ID = "ars/ConicalPendulum-v0", "InvertedPendulum-v5"
SIZES = (1, 2, 4, 8)
TICKS = os.sysconf("SC_CLK_TCK")
# A round in which other processes kept more than this many cores busy is not kept.
QUIET = 0.15


def cpu_times():
    """Busy and total jiffies of the whole machine (``/proc/stat``), and this
    process's own CPU seconds: what else ran during the measurements."""
    with open("/proc/stat") as f:
        fields = [int(x) for x in f.readline().split()[1:]]
    idle = fields[3] + fields[4]
    own = os.times()
    return sum(fields) - idle, sum(fields), own.user + own.system


def actions(space, n, seed=0):
    space.seed(seed)
    return [space.sample() for _ in range(n)]


def rate(step, seconds, warmup=0.3):
    """Calls of ``step()`` per second of wall time, over at least ``seconds``, and how
    many cores other processes kept busy meanwhile (MuJoCo's async workers count as
    others)."""
    end = time.perf_counter() + warmup
    while time.perf_counter() < end:
        step()
    before = cpu_times()
    calls, start = 0, time.perf_counter()
    while True:
        for _ in range(20):
            step()
        calls += 20
        elapsed = time.perf_counter() - start
        if elapsed >= seconds:
            return calls / elapsed, others_since(before, elapsed)


def others_since(before, elapsed):
    """Cores kept busy by other processes since ``before`` (``cpu_times()``)."""
    busy0, _, own0 = before
    busy1, _, own1 = cpu_times()
    return max(((busy1 - busy0) / TICKS - (own1 - own0)) / elapsed, 0.0)


def single(env_id, seconds):
    """Environment steps per second of one ``gymnasium.make`` environment."""
    env = gymnasium.make(env_id)
    env.reset(seed=0)
    todo = actions(env.action_space, 4096)
    i = 0

    def step():
        nonlocal i
        _, _, terminated, truncated, _ = env.step(todo[i % len(todo)])
        i += 1
        if terminated or truncated:
            env.reset()

    result = rate(step, seconds)
    env.close()
    return result


def vector(make, seconds):
    """Environment steps per second (N per vector step) of a vector environment; the
    vector environments reset their ended episodes themselves."""
    envs = make()
    envs.reset(seed=0)
    todo = actions(envs.action_space, 1024)
    i = 0

    def step():
        nonlocal i
        envs.step(todo[i % len(todo)])
        i += 1

    steps, others = rate(step, seconds)
    envs.close()
    return steps * envs.num_envs, others


def ars_vector(n):
    return lambda: ars.gym.make_vec(ARS_ID, num_envs=n)


def mujoco_vector(n, mode):
    return lambda: gymnasium.make_vec(MUJOCO_ID, num_envs=n, vectorization_mode=mode)


def where_the_time_goes(n, steps=2000):
    """Splits ARS's vector step: the time in ``ars.step_many`` (native, GIL released)
    and the rest (Python: checking and applying actions, observing, rewards), and the
    native stepping alone, all at once against one simulation after the other."""
    envs = ars.gym.make_vec(ARS_ID, num_envs=n)
    envs.reset(seed=0)
    todo = actions(envs.action_space, steps)
    before, start_all = cpu_times(), time.perf_counter()
    native = 0.0
    real_step_many = ars.step_many

    def timed_step_many(sims, k):
        nonlocal native
        t = time.perf_counter()
        real_step_many(sims, k)
        native += time.perf_counter() - t

    module = ars.gym.vector.ars
    module.step_many = timed_step_many
    try:
        start = time.perf_counter()
        for a in todo:
            envs.step(a)
        total = time.perf_counter() - start
    finally:
        module.step_many = real_step_many
    sims = [env.sim for env in envs.envs]
    frame = envs.envs[0].frame_skip
    start = time.perf_counter()
    for _ in range(steps):
        ars.step_many(sims, frame)
    together = time.perf_counter() - start
    start = time.perf_counter()
    for _ in range(steps):
        for sim in sims:
            sim.step(frame)
    alone = time.perf_counter() - start
    # The machine's ceiling: one call of many steps, where starting the threads and
    # waiting for them costs nothing.
    start = time.perf_counter()
    ars.step_many(sims, 20_000)
    long_together = time.perf_counter() - start
    start = time.perf_counter()
    for sim in sims:
        sim.step(20_000)
    long_alone = time.perf_counter() - start
    envs.close()
    return {
        "us_per_vector_step": 1e6 * total / steps,
        "us_in_step_many": 1e6 * native / steps,
        "us_in_python": 1e6 * (total - native) / steps,
        "native_speedup": alone / together,
        "ceiling": long_alone / long_together,
        "others": others_since(before, time.perf_counter() - start_all),
    }


def print_table(rows):
    """The Markdown table of environment steps per second: ARS, MuJoCo sync and async."""
    ars_frame, mujoco_frame = 80, 2  # physics steps per environment step
    print()
    print(
        "| environment steps per second | ARS ConicalPendulum-v0 (make_vec: step_many) "
        "| MuJoCo InvertedPendulum-v5, sync | MuJoCo, async |"
    )
    print("| --- | --- | --- | --- |")

    def cell(result, frame=None, unit=""):
        if result is None:
            return "—"
        value, quiet = result
        text = f"{value:,.0f}" + ("" if quiet else " (busy machine)")
        return text + (f" ({value * frame / 1e3:,.0f}k {unit} steps/s)" if frame else "")

    for name, a, m, m_async in rows:
        print(
            f"| {name} | {cell(a, ars_frame, 'ODE')} | {cell(m, mujoco_frame, 'MuJoCo')} "
            f"| {cell(m_async)} |"
        )


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=1.0, help="wall time per measurement")
    parser.add_argument("--repeats", type=int, default=3, help="rounds; the best is kept")
    parser.add_argument("--no-async", action="store_true", help="skip MuJoCo's async vector env")
    args = parser.parse_args()
    import mujoco

    print(
        f"{platform.node()}: {os.cpu_count()} cores ({platform.processor() or platform.machine()}), "
        f"load {os.getloadavg()[0]:.2f}; Python {platform.python_version()}, "
        f"Gymnasium {gymnasium.__version__}, MuJoCo {mujoco.__version__}, ARS {ars.__version__}"
    )
    s = args.seconds
    # Every measurement is taken `--repeats` times, in turn with the others; the best
    # round in which other programs kept at most QUIET cores busy is kept (a 2-core
    # machine shared with a compiler otherwise measures the compiler).
    measures = {("single env", "ars"): lambda: single(ARS_ID, s)}
    measures["single env", "mujoco"] = lambda: single(MUJOCO_ID, s)
    for n in SIZES:
        name = f"vector N={n}"
        measures[name, "ars"] = lambda n=n: vector(ars_vector(n), s)
        measures[name, "mujoco"] = lambda n=n: vector(mujoco_vector(n, "sync"), s)
        if not args.no_async:
            measures[name, "async"] = lambda n=n: vector(mujoco_vector(n, "async"), s)
    rounds = {key: [] for key in measures}
    for _ in range(args.repeats):
        for key, measure in measures.items():
            rounds[key].append(measure())

    def best(key):
        """The best quiet round (any round for MuJoCo's async workers, which are
        other processes themselves) and whether it was quiet."""
        if key not in rounds:
            return None
        quiet = [r for r, others in rounds[key] if others <= QUIET or key[1] == "async"]
        return (max(quiet), True) if quiet else (max(r for r, _ in rounds[key]), False)

    names = ["single env"] + [f"vector N={n}" for n in SIZES]
    rows = [
        (name, best((name, "ars")), best((name, "mujoco")), best((name, "async"))) for name in names
    ]
    noisy = sum(1 for key, rs in rounds.items() if key[1] != "async" for _, o in rs if o > QUIET)
    total = sum(len(rs) for key, rs in rounds.items() if key[1] != "async")
    print(f"{noisy} of {total} rounds had other programs busy (> {QUIET} cores) and were set aside")
    print_table(rows)
    single_ars = rows[0][1][0]
    n1, n2 = rows[1][1][0], rows[2][1][0]
    print()
    print(
        f"ARS make_vec N=2 against the single environment: {n2 / single_ars:.2f}x (issue target 1.7x)"
    )
    print(f"ARS make_vec N=2 against make_vec N=1: {n2 / n1:.2f}x")
    for n in (1, 2):
        split = min(
            (where_the_time_goes(n) for _ in range(args.repeats)), key=lambda r: r["others"]
        )
        print(
            f"ARS vector step N={n}: {split['us_per_vector_step']:.0f} us, of which "
            f"{split['us_in_step_many']:.0f} us in ars.step_many (native) and "
            f"{split['us_in_python']:.0f} us in Python (actions, observations, rewards); "
            f"step_many alone {split['native_speedup']:.2f}x as fast as stepping each in turn "
            f"({split['ceiling']:.2f}x in one call of 20,000 steps); other programs "
            f"{split['others']:.2f} cores"
        )


if __name__ == "__main__":
    main()
