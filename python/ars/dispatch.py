"""Signals between the parts of a simulation and the programs listening to them: the
dispatcher the original ARS programs use (``ars.app.dispatcher``).

``connect(receiver, signal, sender)`` registers a callable; ``send(signal, sender,
**named)`` calls every live receiver registered for that signal (or for any signal)
and that sender (or any sender), each once, in the order connected, passing
``signal=``, ``sender=`` and the named values the receiver declares (all of them if it
takes ``**kwargs``). Receivers are held weakly by default: a bound method disappears
with its object. Connecting the same receiver again for the same signal and sender
replaces the earlier registration.

One difference from the original, on purpose: a method of a program (an
``ars.app.Program``) connected with ``sender=Any`` hears the signals of that program's
own simulation only (sent by the simulation, or by a sensor of its bodies, joints or
space), never those of another program's simulation created later in the same process.
"""

import inspect
import weakref

__all__ = ["Anonymous", "Any", "DispatcherError", "connect", "disconnect", "heard", "send"]


class _Marker:
    def __init__(self, name):
        self._name = name

    def __repr__(self):
        return self._name


Any = _Marker("Any")
"""Any signal, or any sender."""

Anonymous = _Marker("Anonymous")
"""The sender of a signal sent without one."""


class DispatcherError(Exception):
    """A receiver that cannot be registered."""


class _Receiver:
    """A registered callable: held weakly (or not), with the names it accepts."""

    __slots__ = ("_ref", "_strong", "accepted", "accepts_all", "key", "owner")

    def __init__(self, receiver, weak):
        self.key = _key(receiver)
        self._strong = None
        self._ref = None
        if not weak:
            self._strong = receiver
        elif inspect.ismethod(receiver):
            self._ref = weakref.WeakMethod(receiver)
        else:
            try:
                self._ref = weakref.ref(receiver)
            except TypeError:
                self._strong = receiver  # builtins cannot be referenced weakly
        self.accepts_all, self.accepted = _parameters(receiver)
        owner = getattr(receiver, "__self__", None)
        self.owner = weakref.ref(owner) if _is_program(owner) else None

    def get(self):
        return self._strong if self._ref is None else self._ref()


def _key(receiver):
    if inspect.ismethod(receiver):
        return (id(receiver.__self__), id(receiver.__func__))
    return id(receiver)


def _parameters(receiver):
    try:
        params = inspect.signature(receiver).parameters.values()
    except (TypeError, ValueError):
        return True, frozenset()
    if any(p.kind is p.VAR_KEYWORD for p in params):
        return True, frozenset()
    names = {p.name for p in params if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)}
    return False, frozenset(names)


def _is_program(obj):
    # Imported late: ars.app imports this module.
    if obj is None:
        return False
    from ars.app import Program

    return isinstance(obj, Program)


# (sender key, signal) -> list of _Receiver, in the order connected.
_registry = {}
# The signals some receiver is registered for (``Any`` among them if one hears every
# signal): a signal outside it has no receiver, whoever sends it.
_heard = set()


def _registry_changed():
    _heard.clear()
    _heard.update(signal for (_, signal), receivers in _registry.items() if receivers)


def heard(signal):
    """Whether some receiver may hear ``signal`` (from some sender): when not, sending
    it does nothing, and a sender may skip preparing it."""
    return signal in _heard or Any in _heard


# Senders that cannot be referenced weakly, kept alive so that their ids stay theirs.
_kept = {}


def _forget(sender_id):
    for key in [k for k in _registry if k[0] == sender_id]:
        del _registry[key]
    _kept.pop(sender_id, None)
    _registry_changed()


def _watch(sender):
    """Forgets a sender's registrations when it goes away (its id may be reused)."""
    sender_id = id(sender)
    if any(k[0] == sender_id for k in _registry):
        return
    try:
        weakref.finalize(sender, _forget, sender_id)
    except TypeError:
        _kept[sender_id] = sender


def _sender_key(sender):
    return sender if sender is Any or sender is Anonymous else id(sender)


def connect(receiver, signal=Any, sender=Any, weak=True):
    """Calls ``receiver`` whenever ``signal`` (``Any``: every signal) is sent by
    ``sender`` (``Any``: any sender)."""
    if not callable(receiver):
        raise DispatcherError(f"a receiver must be callable, got {receiver!r}")
    if signal is None:
        raise DispatcherError("the signal cannot be None")
    key = (_sender_key(sender), signal)
    if sender is not Any and sender is not Anonymous:
        _watch(sender)
    entry = _Receiver(receiver, weak)
    receivers = _registry.setdefault(key, [])
    receivers[:] = [r for r in receivers if r.key != entry.key]
    receivers.append(entry)
    _registry_changed()


def disconnect(receiver, signal=Any, sender=Any):
    """Stops calling ``receiver`` for ``signal`` from ``sender``."""
    key = (_sender_key(sender), signal)
    receivers = _registry.get(key)
    target = _key(receiver)
    if not receivers or not any(r.key == target for r in receivers):
        raise DispatcherError(f"{receiver!r} is not connected to {signal!r} from {sender!r}")
    receivers[:] = [r for r in receivers if r.key != target]
    _registry_changed()


def _live(key):
    receivers = _registry.get(key)
    if not receivers:
        return []
    live = []
    for r in receivers:
        fn = r.get()
        if fn is None:
            continue
        live.append((r, fn))
    if len(live) != len(receivers):
        receivers[:] = [r for r, _ in live]
        _registry_changed()
    return live


def _program_of(sender):
    """The program whose simulation a signal comes from: the sender's own (a
    simulation's ``_program``), else that of the simulation the sender is part of (a
    body's or joint's ``_sim``), or of its source (a sensor's ``_source``)."""
    for _ in range(4):
        if sender is None:
            return None
        owner = getattr(sender, "_program", None)
        if owner is not None:
            return owner()
        sim = getattr(sender, "_sim", None)
        sender = sim() if sim is not None else getattr(sender, "_source", None)
    return None


_UNKNOWN = object()


def send(signal, sender=Anonymous, *args, **named):
    """Sends ``signal`` from ``sender``; returns ``[(receiver, response), ...]``. An
    exception raised by a receiver stops the sending and propagates."""
    # Most signals (a joint's torque, every step's) have no receiver at all: that
    # costs two set lookups and nothing else.
    if signal not in _heard and Any not in _heard:
        return []
    sender_key = _sender_key(sender)
    registry = _registry
    mine, mine_any = (sender_key, signal), (sender_key, Any)
    everyones, everyones_any = (Any, signal), (Any, Any)
    keys = (mine, mine_any) if sender_key is Any else (mine, mine_any, everyones, everyones_any)
    seen = set()
    responses = []
    program = _UNKNOWN  # the sender's program, found when a receiver needs it
    for key in keys:
        if key not in registry:
            continue
        for entry, fn in _live(key):
            if entry.key in seen:
                continue
            seen.add(entry.key)
            if entry.owner is not None:
                if program is _UNKNOWN:
                    program = _program_of(sender)
                if program is not None and entry.owner() is not program:
                    continue
            if entry.accepts_all:
                values = dict(named, signal=signal, sender=sender)
            else:
                values = {k: v for k, v in named.items() if k in entry.accepted}
                if "signal" in entry.accepted:
                    values["signal"] = signal
                if "sender" in entry.accepted:
                    values["sender"] = sender
            responses.append((fn, fn(*args, **values)))
    return responses
