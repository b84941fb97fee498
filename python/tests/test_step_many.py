"""`ars.step_many`: many simulations stepped at once on native threads, each exactly as
it steps alone; bad input refused before anything steps; a hook's exception raised,
the other simulations stepped on."""

import math
import threading

import numpy as np
import pytest

import ars


def bits(array):
    """The exact bytes of a float64 array."""
    return np.ascontiguousarray(array, dtype=np.float64).tobytes()


def falling_box(i):
    """A box falling onto the floor, spun: contacts and rotation, different for each
    `i`, with a Python pre-step hook pushing it (the hook's GIL round trip is part of
    what step_many has to get right)."""
    sim = ars.Simulation()
    sim.add_floor()
    sim.add_box((0.2, 0.1, 0.3), (0.0, 0.5 + 0.1 * i, 0.0), mass=1.0, name="box")
    box = sim.body("box")
    box.set_angular_velocity((1.0 + i, 0.5, -0.3 * i))
    sim.add_pre_step(lambda: box.add_force((0.3 * math.sin(sim.time * 20.0), 0.0, 0.1 * i)))
    return sim


def state(sim):
    box = sim.body("box")
    return (
        sim.step_count,
        bits(box.position),
        bits(box.rotation),
        bits(box.linear_velocity),
        bits(box.angular_velocity),
    )


# ars.step_many


def test_step_many_steps_each_simulation_as_stepping_it_alone_bit_for_bit():
    alone = [falling_box(i) for i in range(5)]
    together = [falling_box(i) for i in range(5)]
    for sim in alone:
        sim.step(2000)
    ars.step_many(together, 800)
    ars.step_many(together, 1200)
    assert [state(s) for s in together] == [state(s) for s in alone]
    # They did fall and hit the floor, differently.
    assert len({state(s)[1] for s in together}) == 5
    assert all(s.body("box").position[1] < 0.3 for s in together)


def test_step_many_takes_any_iterable_and_no_simulation_or_zero_steps():
    sims = [falling_box(0), falling_box(1)]
    ars.step_many(iter(sims), 2)
    ars.step_many((s for s in sims), 0)
    ars.step_many([], 10)
    assert [s.step_count for s in sims] == [2, 2]


@pytest.mark.parametrize(
    "make_args, error, message",
    [
        (lambda a, b: ([a, b, a], 5), ars.InputError, "items 0 and 2 are the same simulation"),
        (lambda a, b: ([a, "b"], 5), TypeError, "item 1 is of type str"),
        (lambda a, b: ([a, b], -1), ars.InputError, "must be 0 or more"),
        (lambda a, b: (a, 5), TypeError, "not iterable"),
    ],
)
def test_step_many_refuses_bad_input_before_anything_steps(make_args, error, message):
    a, b = falling_box(0), falling_box(1)
    before = [state(a), state(b)]
    args = make_args(a, b)
    with pytest.raises(error, match=message):
        ars.step_many(*args)
    assert [state(a), state(b)] == before
    ars.step_many([a, b], 3)  # still usable
    assert a.step_count == b.step_count == 3


def test_a_hook_that_raises_stops_its_simulation_and_the_others_step_on():
    good = [falling_box(0), falling_box(2)]
    bad = falling_box(1)
    reference = [falling_box(0), falling_box(2)]

    class Boom(Exception):
        pass

    def explode():
        if bad.step_count == 40:
            raise Boom("at step 40")

    hook = bad.add_pre_step(explode)
    with pytest.raises(Boom, match="at step 40"):
        ars.step_many([good[0], bad, good[1]], 100)
    # The one that raised stopped where its hook raised, whole; the others took
    # their 100 steps, as alone.
    assert bad.step_count == 40
    for sim in reference:
        sim.step(100)
    assert [state(s) for s in good] == [state(s) for s in reference]
    bad.remove_hook(hook)
    ars.step_many([bad], 10)
    assert bad.step_count == 50


def test_the_first_raising_simulation_in_the_list_is_the_one_raised():
    sims = [falling_box(i) for i in range(3)]

    def raiser(i):
        def hook():
            raise RuntimeError(f"sim {i}")

        return hook

    for i in (1, 2):
        sims[i].add_pre_step(raiser(i))
    with pytest.raises(RuntimeError, match="sim 1"):
        ars.step_many(sims, 5)
    # Neither exception is left behind for a later call.
    sims[0].step(1)
    assert sims[0].step_count == 6


def test_a_hook_cannot_step_its_own_simulation_through_step_many():
    sim = falling_box(0)
    other = falling_box(1)
    seen = []

    def hook():
        if not seen:
            try:
                ars.step_many([other, sim], 1)
            except ars.BusyError as e:
                seen.append(str(e))

    sim.add_pre_step(hook)
    sim.step(2)
    assert seen and "item 1" in seen[0]
    assert other.step_count == 0


def test_step_many_waits_for_a_simulation_stepping_on_another_thread():
    sims = [falling_box(i) for i in range(3)]
    reference = [falling_box(i) for i in range(3)]
    thread = threading.Thread(target=sims[1].step, args=(2000,))
    thread.start()
    ars.step_many(sims, 500)
    thread.join()
    for sim, n in zip(reference, (500, 2500, 500)):
        sim.step(n)
    assert [state(s) for s in sims] == [state(s) for s in reference]


def test_a_hook_may_step_other_simulations_with_step_many():
    # The hook runs on whichever thread steps its simulation, a pool worker too:
    # there its step_many runs on that thread alone, and nothing waits for ever.
    outer = [falling_box(0), falling_box(1)]
    inner = [[falling_box(2), falling_box(3)], [falling_box(4), falling_box(5)]]
    for sim, pair in zip(outer, inner):
        sim.add_post_step(lambda pair=pair: ars.step_many(pair, 2))
    ars.step_many(outer, 50)
    reference = [falling_box(i) for i in range(2, 6)]
    for sim in reference:
        sim.step(100)
    assert [state(s) for pair in inner for s in pair] == [state(s) for s in reference]


def test_calls_from_several_threads_at_once_each_step_their_own_simulations():
    groups = [[falling_box(i), falling_box(i + 1), falling_box(i + 2)] for i in (0, 3, 6)]
    errors = []

    def run(group):
        try:
            for _ in range(20):
                ars.step_many(group, 25)
        except Exception as e:  # noqa: BLE001 - reported by the assertion below
            errors.append(e)

    threads = [threading.Thread(target=run, args=(g,)) for g in groups]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    reference = [falling_box(i) for i in range(9)]
    for sim in reference:
        sim.step(500)
    assert [state(s) for g in groups for s in g] == [state(s) for s in reference]
