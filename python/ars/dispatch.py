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

import weakref
from types import FunctionType, MethodType

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
    """A registered callable: held weakly (or not), with the names it accepts. A method
    is held as a weak reference to its object and its function (what
    ``weakref.WeakMethod`` does, without a Python-level call to reach it)."""

    __slots__ = ("_func", "_ref", "_strong", "accepted", "accepts_all", "bare", "key", "owner")

    def __init__(self, receiver, weak):
        self.key = _key(receiver)
        self._strong = None
        self._ref = None
        self._func = None
        if not weak:
            self._strong = receiver
        elif isinstance(receiver, MethodType):
            self._ref = weakref.ref(receiver.__self__)
            self._func = receiver.__func__
        else:
            try:
                self._ref = weakref.ref(receiver)
            except TypeError:
                self._strong = receiver  # builtins cannot be referenced weakly
        self.accepts_all, self.accepted = _parameters(receiver)
        # Takes none of the values a signal carries: called with none.
        self.bare = not self.accepts_all and not self.accepted & {"signal", "sender"}
        owner = getattr(receiver, "__self__", None)
        self.owner = weakref.ref(owner) if _is_program(owner) else None

    def get(self):
        """The receiver, or ``None`` once it is gone."""
        if self._ref is None:
            return self._strong
        target = self._ref()
        if target is None or self._func is None:
            return target
        return MethodType(self._func, target)


def _key(receiver):
    if isinstance(receiver, MethodType):
        return (id(receiver.__self__), id(receiver.__func__))
    return id(receiver)


_CO_VARKEYWORDS = 0x08  # inspect.CO_VARKEYWORDS: the code takes **kwargs


def _parameters(receiver):
    """``(accepts every name, the names it accepts)`` of a receiver's parameters."""
    function = receiver.__func__ if isinstance(receiver, MethodType) else receiver
    if isinstance(function, FunctionType) and not hasattr(function, "__wrapped__"):
        # A plain function's names are in its code: no need for ``inspect.signature``
        # (whose module takes longer to import than the rest of ``ars.app``).
        code = function.__code__
        if code.co_flags & _CO_VARKEYWORDS:
            return True, frozenset()
        named = code.co_varnames[
            code.co_posonlyargcount : code.co_argcount + code.co_kwonlyargcount
        ]
        if isinstance(receiver, MethodType):
            named = named[1:] if code.co_posonlyargcount == 0 else named  # its ``self``
        return False, frozenset(named)
    import inspect  # anything else: builtins, callable objects, wrapped functions

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
# (sender key, signal) -> the receivers a send of it reaches, before the program
# filter: what ``send`` found the last time, kept until the registry changes (a
# simulation sends its step signals thousands of times a second).
_resolved = {}


# Told (held weakly) whenever the heard signals may have changed.
_watchers = []


def _watch_heard(method):
    """Calls the bound ``method`` whenever a receiver is connected or goes away, for
    as long as its object lives: a sender may then turn off what prepares a signal no
    one hears."""
    _watchers.append(weakref.WeakMethod(method))


def _registry_changed():
    _heard.clear()
    _heard.update(signal for (_, signal), receivers in _registry.items() if receivers)
    _resolved.clear()
    if _watchers:
        live = [ref for ref in _watchers if ref() is not None]
        _watchers[:] = live
        for ref in live:
            watcher = ref()
            if watcher is not None:
                watcher()


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


def _direct_calls(signal, sender):
    """What ``send(signal, sender)`` (with no values) calls now, as ``(reference,
    function)`` pairs a sender can call itself, in order: ``function(reference())`` for
    a method, ``reference()()`` for a function held weakly, ``function()`` for one held
    strongly (``reference`` is ``None``); a reference that returns ``None`` is a
    receiver gone since. ``None`` when some receiver takes the signal's values (then
    ``send`` it). What it returns holds until a receiver is connected or goes away
    (``_watch_heard``) or the sender's program changes."""
    if signal not in _heard and Any not in _heard:
        return []
    program = _UNKNOWN
    calls = []
    for entry in _resolve(_sender_key(sender), signal):
        if not entry.bare:
            return None
        if entry.owner is not None:
            if program is _UNKNOWN:
                program = _program_of(sender)
            if program is not None and entry.owner() is not program:
                continue
        calls.append((entry._ref, entry._func if entry._ref is not None else entry._strong))
    return calls


def _resolve(sender_key, signal):
    """The live receivers of ``signal`` from ``sender_key``, each once, in the order
    they are called (the sender's own first, then everyone's)."""
    if sender_key is Any:
        keys = ((Any, signal), (Any, Any))
    else:
        keys = ((sender_key, signal), (sender_key, Any), (Any, signal), (Any, Any))
    seen = set()
    found = []
    for key in keys:
        for entry, _ in _live(key):
            if entry.key not in seen:
                seen.add(entry.key)
                found.append(entry)
    return found


def send(signal, sender=Anonymous, *args, **named):
    """Sends ``signal`` from ``sender``; returns ``[(receiver, response), ...]``. An
    exception raised by a receiver stops the sending and propagates."""
    # Most signals (a joint's torque, every step's) have no receiver at all: that
    # costs two set lookups and nothing else.
    if signal not in _heard and Any not in _heard:
        return []
    sender_key = _sender_key(sender)
    resolved = _resolved.get((sender_key, signal))
    if resolved is None:
        resolved = _resolve(sender_key, signal)
        # (Resolving may prune dead receivers, which empties the cache: store after.)
        _resolved[(sender_key, signal)] = resolved
    responses = []
    program = _UNKNOWN  # the sender's program, found when a receiver needs it
    for entry in resolved:
        fn = entry.get()
        if fn is None:
            # Gone since it was resolved (maybe during this send): skipped, and
            # forgotten when the next send resolves again.
            _resolved.pop((sender_key, signal), None)
            continue
        if entry.owner is not None:
            if program is _UNKNOWN:
                program = _program_of(sender)
            if program is not None and entry.owner() is not program:
                continue
        if entry.bare and not named:
            responses.append((fn, fn(*args)))
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
