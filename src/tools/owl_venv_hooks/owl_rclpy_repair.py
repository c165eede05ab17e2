"""The venv's repairs of rclpy 7.1 (Jazzy): Ctrl-C as the course expects it, takes, service calls.

Ctrl-C in a program that called a plain rclpy.init() (the course's listings, the official
tutorials): Jazzy's rclpy installs a SIGINT handler that shuts every context down, so the course's
clean-up after rclpy.spin (the appendix's torque-off call, destroy_node, rclpy.shutdown) fails with
"RCLError: failed to shutdown: rcl_shutdown already called", spin may end with
ExternalShutdownException instead of KeyboardInterrupt, and a listing with no try/except ends with
a KeyboardInterrupt traceback. With this repair, such an rclpy.init installs no rclpy handler
(SIGTERM ends the process, as Python's default, rather than shutting ROS down under the course's
clean-up), and Ctrl-C behaves as on Humble, the course's distribution: it raises CtrlC, a
KeyboardInterrupt, in the main thread and ROS stays up until the program calls rclpy.shutdown().
Executors blocked in their wait are woken as rclpy's own handler wakes them (their SIGINT guard
conditions are triggered, by a thread that reads Python's signal wake-up fd), so the Ctrl-C lands
at once. CtrlC is also a SystemExit without a code: a program that does not catch it ends quietly
with exit status 0, as after sys.exit(), instead of printing a traceback. A SIGINT within SAME_PRESS
of the last is the same Ctrl-C passed on by `ros2 launch` and is not raised again. When the interpreter
exits after a Ctrl-C, the default context is shut down before Python joins the program's threads,
so an executor spinning in a thread of its own stops as it did with rclpy's handler; a Ctrl-C
that lands while Python joins those threads (after the program's main code ended) does the same
instead of raising where nothing can catch it. A Ctrl-C that lands while Python runs a finalizer
(the executor drops a Task after each callback: Future.__del__) would be printed there as "Exception
ignored" and lost, the node spinning on, and one in a __set_name__ would become a RuntimeError
traceback; each is given back to the main thread once that code is over. So is one that lands
where Python drops it anyway (sys.unraisablehook), e.g. in a weakref callback: importlib's, as a
module lock is freed at startup. Code that asks for upstream's behaviour keeps it:
signal_handler_options given to rclpy.init, a SIGINT handler or wake-up fd of the program's own,
rclpy.init outside the main thread or for another context.

The repair of Ctrl-C that lands while rclpy builds a message (a defect of the rclpy wheel):

Python raises KeyboardInterrupt at the next point where the main thread runs Python code. When the
Ctrl-C arrives while rclpy's executor takes a message, request or response from DDS, that point is
the Python constructor of the message that rclpy's C++ code is building, and pybind11 replaces the
KeyboardInterrupt with "RuntimeError: Unable to convert call argument '0' to Python object" (a
message, a response) or with "SystemError: ... returned a result with an exception set" whose cause
is the KeyboardInterrupt (a service's request). A node
written as the course writes it (`except KeyboardInterrupt:` around rclpy.spin) then ends with a
traceback and exit code 1: about 1 stop in 3 under a flood of messages, 1-3 % at the IMU's 100 Hz,
with rclpy's own Ctrl-C handler and with SignalHandlerOptions.NO alike. Upstream rclpy has it too.

scripts/bootstrap.sh copies this module into the venv's site-packages with a .pth line that calls
install() at every start of the venv's Python; nothing happens until rclpy is imported.
Then the executor's take methods (TAKES: a message, a service's request or response, an action's
data; a few microseconds each, never the callback that follows) are wrapped, for calls in the main
thread (the only one where Python raises KeyboardInterrupt) while SIGINT has Python's default handler
or CtrlC's:
- a plain rclpy.init, or SignalHandlerOptions.NO (a Python handler alone): a Ctrl-C during the take
  is held and raised as the take returns, never inside it.
- rclpy's handler (SignalHandlerOptions.ALL or SIGINT given): it cannot be swapped for a while,
  as signal.signal would also replace rclpy's handler in the kernel. The SystemError carries the
  KeyboardInterrupt as its cause and is turned back into it. rclpy's handler shuts the context down
  and then calls Python's, so the RuntimeError, which carries nothing, is turned back into a
  KeyboardInterrupt when the context goes down within SHUTDOWN_GRACE; otherwise it is a real error
  and stays as it is.
A program with a SIGINT handler of its own, and executors spinning in other threads, are untouched.

A Ctrl-C that lands while the executor handles a message, request or response, around the take,
used to leave the executor unable to handle anything of that node again, and the course's clean-up
after Ctrl-C (the appendix's torque-off call) waited forever for its response: rclpy claims the
node's callback group and marks the entity as handled before the take, and gives both back only
when the callback ends or the take is done; a KeyboardInterrupt raised in between escapes the
handler with both still taken (seen once in 80 Ctrl-C of the 5.3 listing in a suite). A handler
cut short by a Ctrl-C now gives its entity and its callback group back, and is cancelled. A Ctrl-C
that lands while the executor files a handler (it has marked the entity, the handler is not yet
in its list) is held until it is filed, as in a take.

rclpy's ActionClient sends a goal, cancel or result request first and files the Future that its
response completes afterwards, unlocked: when the executor spins in another thread (a GUI, a test
harness) and the response is taken in between, it is dropped ("Ignoring unexpected cancel
response") and the caller waits forever. Sending and filing now happen under a lock of the client,
and the client's execute() waits for that lock before it looks a response up.

A service client slowed down with every call (3.6 ms per call over its first 300 calls, 42 ms over
calls 1200-1500): each spin_until_future_complete (and each of its spin_once_ rounds) gives the
future a done-callback that wakes the executor, and once the future is done rclpy makes each such
callback a Task of the executor; the loop returns as soon as the future is done, so the Tasks stay
in the executor's list (3 more per call) and every later wait walks and copies that list. After
either method returns, its wake-ups are dropped: removed from a future still pending, or as Tasks
not yet run (a wake-up only ends a wait, and that wait is over).

The same Ctrl-C can land inside the constructor of one of the Tasks the executor makes for each
callback, before the attribute its __del__ reads is set: the node still stops as it should, but
Python prints "Exception ignored in: <function Future.__del__ ...> ... AttributeError: 'Task'
object has no attribute '_exception'" on the way out. Future.__del__ is made to skip a future
whose construction was interrupted (it has no exception to report). A Task the executor had made
for a handler that never ran before the program ended printed "sys:1: RuntimeWarning: coroutine
'Executor._make_handler.<locals>.handler' was never awaited" at exit (seen once in a suite run, at
display_camera's Ctrl-C); Future.__del__ now closes such a Task's coroutine, quietly.

An executor still alive when the interpreter exits (kept by a reference cycle with its node) may be
finalised after its SIGINT guard condition, which destroys itself first: Executor.__del__ then
printed "Exception ignored in: <function Executor.__del__ ...> ... InvalidHandle: cannot use
Destroyable because destruction was requested" (seen at the end of `ros2 topic echo --once`).
Executor.__del__ now leaves a guard condition that is already gone alone, as the guard's own
__del__ does, and one that was never made: a Ctrl-C in Executor.__init__ (rclpy.spin makes an
executor; seen once in 20 Ctrl-C of a listing) printed "... AttributeError: 'SingleThreadedExecutor'
object has no attribute '_sigint_gc'". The SIGINT guard condition's own __del__ likewise skips a
guard whose __init__ a Ctrl-C cut short before its handle was made (that executor's guard: "...
AttributeError: 'SignalHandlerGuardCondition' object has no attribute '_GuardCondition__gc'", seen
once in a suite run, at control_servo's Ctrl-C just as it had enabled the torque).

A Ctrl-C that lands after the executor filed a timer's handler and before it ran leaves that
handler in the executor's list, and rclpy runs it at the next spin. A clean-up that cancels the
timer first and then spins for its service responses (keyboard_servos: no goal may follow the
torque-off) then ended with "RCLError: failed to call timer: timer is canceled" (seen once in 11
suite runs). The take of a timer cancelled in between now finds no work, as for a destroyed one.

Not rclpy's, but the same kind of wheel defect: every generated message module of Jazzy imports
rosidl_generator_py for its import_type_support, and that package's __init__ also imports its code
generator (generate_py_impl: lark, empy, rosidl_parser), which only a build uses: 35-45 ms of every
node's start. The generator module is now made when imported but run at its first use: its
generate_py, the one name the package's __init__ takes, forwards to the real function, and any
other name loads the real module first.

At the first import of rclpy, before its extension loads Fast DDS, this hook also loads the venv's
repair of Fast DDS's enable order (owl_fastdds_enable_order.c, built by make setup): a new
participant listens before it announces itself, so it hears every running participant's answer.
"""

from __future__ import annotations

import _signal  # type: ignore[import-not-found]  # the C half of signal: typeshed has no stub
import _thread
import contextlib
import os
import signal
import sys
import threading
import time
import weakref
from collections.abc import Callable
from functools import wraps
from typing import TYPE_CHECKING, Any, ClassVar

from owl_gui_hook import PatchingLoader, find_spec_after

if TYPE_CHECKING:
    from collections.abc import Sequence
    from importlib.machinery import ModuleSpec
    from types import FrameType, ModuleType

TAKES = ('_take_subscription', '_take_client', '_take_service', '_take_waitable')
SPINS_UNTIL_FUTURE = ('spin_until_future_complete', 'spin_once_until_future_complete')
SENDS = ('send_goal_async', '_cancel_goal_async', '_get_result_async')  # ActionClient's requests
CONVERSION_ERROR = 'Unable to convert call argument'
SHUTDOWN_GRACE = 0.5  # s for rclpy's signal thread to shut the context down after its handler ran
REDELIVER = 0  # a byte on the wake-up fd that is no signal's number: see raise_ctrl_c
REDELIVER_AFTER = 0.002  # s: longer than a finalizer runs
FASTDDS_ENABLE_ORDER = 'libowl_fastdds_enable_order.so'  # in the venv's lib/, built by make setup
SAME_PRESS = 0.3  # s: SIGINTs this close together are one Ctrl-C (the terminal's and a launcher's)


class RclpyImportHook:
    """A sys.meta_path entry that acts on the first import of each module in patches()."""

    patched: ClassVar[set[str]] = set()

    @classmethod
    def find_spec(cls, fullname: str, path: Sequence[str] | None = None,
                  target: ModuleType | None = None) -> ModuleSpec | None:
        """At the first import of each module in patches(): its spec with a patching loader; else None."""
        patch = patches().get(fullname)
        if patch is None or fullname in cls.patched:
            return None
        if fullname == 'rclpy':
            load_fastdds_enable_order()
        cls.patched.add(fullname)
        if cls.patched >= set(patches()):
            sys.meta_path.remove(cls)
        spec = find_spec_after(cls, fullname, target, path)
        if spec is None or spec.loader is None:
            return None
        spec.loader = PatchingLoader(spec.loader, patch)  # type: ignore[assignment]  # duck-typed loader
        return spec


def patches() -> dict[str, Callable[[Any], None]]:
    """The modules this repair acts on, each with the function that patches it once it is imported."""
    return {'rclpy.signals': patch_signals, 'rclpy': patch_init,
            'rclpy.executors': patch_executors, 'rclpy.action.client': patch_action_client}


class CtrlC(KeyboardInterrupt, SystemExit):
    """Ctrl-C in a ROS program: caught by `except KeyboardInterrupt`; uncaught, a quiet exit 0."""


class CtrlCAsOnHumble:
    """SIGINT raising CtrlC in the main thread, with every executor's wait woken (see above)."""

    sigint_guards: ClassVar[weakref.WeakSet[Any]] = weakref.WeakSet()
    installed = False
    wake_up_fd = -1  # the write end of Python's signal wake-up fd, read by the owl-ctrl-c thread
    pressed_at: float | None = None  # time.monotonic() of the last Ctrl-C
    python_unraisablehook: Callable[[Any], object] = sys.__unraisablehook__  # the one before ours
    holding = False  # the main thread is in hold_ctrl_c: a Ctrl-C is only noted, as held
    held = False

    @classmethod
    def take_over(cls) -> bool:
        """Install it unless the program handles SIGINT or the wake-up fd itself; whether it is on."""
        if cls.installed:
            return signal.getsignal(signal.SIGINT) is raise_ctrl_c
        if (threading.current_thread() is not threading.main_thread()
                or signal.getsignal(signal.SIGINT) is not signal.default_int_handler):
            return False
        read_end, write_end = os.pipe()
        os.set_blocking(write_end, False)
        previous = signal.set_wakeup_fd(write_end, warn_on_full_buffer=False)
        if previous != -1:
            signal.set_wakeup_fd(previous)
            os.close(read_end)
            os.close(write_end)
            return False
        signal.signal(signal.SIGINT, raise_ctrl_c)
        cls.wake_up_fd = write_end
        threading.Thread(target=cls.wake_executors, args=(read_end,), name='owl-ctrl-c',
                         daemon=True).start()
        threading._register_atexit(cls.shut_down_after_ctrl_c)  # type: ignore[attr-defined]
        cls.python_unraisablehook = sys.unraisablehook
        sys.unraisablehook = cls.give_back_unraisable
        cls.installed = True
        return True

    @classmethod
    def wake_executors(cls, read_end: int) -> None:
        """The owl-ctrl-c thread: at each SIGINT on the wake-up fd, trigger every SIGINT guard condition.

        That wakes the executors blocked in their wait, as rclpy's own handler does. At each
        REDELIVER (give_back_later), it gives the main thread the Ctrl-C again a moment later. It
        never returns.
        """
        while True:
            received = os.read(read_end, 64)
            if signal.SIGINT in received:
                for guard in list(cls.sigint_guards):
                    try:
                        guard.trigger()
                    except Exception:  # destroyed meanwhile: nothing left to wake
                        pass
            if REDELIVER in received:
                time.sleep(REDELIVER_AFTER)
                _thread.interrupt_main(signal.SIGINT)

    @classmethod
    def give_back_later(cls) -> None:
        """Have the owl-ctrl-c thread give the main thread this Ctrl-C again REDELIVER_AFTER from now.

        For a Ctrl-C that Python cannot raise where it landed: it would print it ("Exception ignored
        in: ...") and drop it, and the node would go on spinning. (Not _thread.interrupt_main here:
        Python would call the handler again at once, where it is.)
        """
        with contextlib.suppress(OSError):  # a full pipe holds a REDELIVER already
            os.write(cls.wake_up_fd, bytes([REDELIVER]))

    @classmethod
    def give_back_unraisable(cls, unraisable: Any) -> None:
        """sys.unraisablehook: a CtrlC raised where Python drops exceptions is given back later.

        A finalizer is kept out in raise_ctrl_c; this catches the rest, e.g. a weakref callback
        (importlib's, as a module lock is freed at startup: seen in a suite).
        """
        if isinstance(unraisable.exc_type, type) and issubclass(unraisable.exc_type, CtrlC):
            cls.pressed_at = None  # the same press, raised again: not a copy to ignore
            cls.give_back_later()
            return
        cls.python_unraisablehook(unraisable)

    @classmethod
    def shut_down_after_ctrl_c(cls) -> None:
        """At exit after a Ctrl-C: ROS down, so threads still spinning end and Python can join them.

        Another Ctrl-C (the launcher's copy) is ignored from here: Python soon gives SIGINT back its
        default action, which would kill the process before DDS says goodbye, and other nodes
        would list this one until its lease ran out.
        """
        if cls.pressed_at is not None:
            signal.signal(signal.SIGINT, signal.SIG_IGN)
            import rclpy
            rclpy.try_shutdown()


def raise_ctrl_c(signum: int, frame: FrameType | None) -> None:
    """SIGINT's handler: raise CtrlC, unless it is held (hold_ctrl_c) or follows the last within SAME_PRESS.

    One Ctrl-C, one CtrlC: the copy that `ros2 launch` passes on to a node that the terminal
    already signalled must not cut the clean-up that the first one started.
    """
    if CtrlCAsOnHumble.holding:
        CtrlCAsOnHumble.held = True
        return
    now = time.monotonic()
    last = CtrlCAsOnHumble.pressed_at
    if last is not None and now - last < SAME_PRESS:
        return
    shutting_down = in_threading_shutdown(frame)
    if in_code_that_loses_exceptions(frame) and not shutting_down:
        CtrlCAsOnHumble.give_back_later()  # once that code is over, which runs to its end
        return
    CtrlCAsOnHumble.pressed_at = now
    if shutting_down:
        import rclpy
        rclpy.try_shutdown()
        return
    raise CtrlC


def in_code_that_loses_exceptions(frame: FrameType | None) -> bool:
    """Whether the main thread runs code whose exceptions never reach the program as they are.

    Python runs a signal handler at any function call. An exception raised in a finalizer (__del__:
    the executor drops a Task, Future.__del__, after each callback) is printed and dropped; one
    raised in a __set_name__ (as a class is made, e.g. numpy's while the node's first service imports
    it: seen once in 20 Ctrl-C of a listing) becomes a RuntimeError (Python 3.11).
    """
    while frame is not None:
        if frame.f_code.co_name in ('__del__', '__set_name__'):
            return True
        frame = frame.f_back
    return False


def in_threading_shutdown(frame: FrameType | None) -> bool:
    """Whether the main thread runs threading._shutdown: the program is over, Python joins its threads.

    A CtrlC raised there would only be printed ("Exception ignored in: <module 'threading'>"); what
    the Ctrl-C must do instead is stop ROS, so that threads still spinning end and Python can join
    them. A late copy of the Ctrl-C that ended the program lands there too when the machine is busy.
    """
    shutdown_code = threading._shutdown.__code__  # type: ignore[attr-defined]
    while frame is not None:
        if frame.f_code is shutdown_code:
            return True
        frame = frame.f_back
    return False


def patch_signals(signals: Any) -> None:
    """Patch rclpy.signals: every SIGINT guard condition made is tracked, for wake_executors to trigger.

    Its handler options are kept for rclpy_handles_ctrl_c; a guard left half built is deleted quietly.
    """
    guard_init = signals.SignalHandlerGuardCondition.__init__

    @wraps(guard_init)
    def init_and_track(self: Any, *args: Any, **kwargs: Any) -> None:
        guard_init(self, *args, **kwargs)
        CtrlCAsOnHumble.sigint_guards.add(self)

    signals.SignalHandlerGuardCondition.__init__ = init_and_track
    guard_del = signals.SignalHandlerGuardCondition.__del__

    @wraps(guard_del)
    def __del__(self: Any) -> None:  # named so that in_code_that_loses_exceptions knows it
        if '_GuardCondition__gc' in vars(self):  # else a Ctrl-C cut __init__ short: nothing was made
            guard_del(self)

    signals.SignalHandlerGuardCondition.__del__ = __del__
    RclpyHandlerOptions.current = signals.get_current_signal_handlers_options
    options = signals.SignalHandlerOptions
    RclpyHandlerOptions.with_sigint = frozenset({options.ALL.value, options.SIGINT.value})


def load_fastdds_enable_order() -> None:
    """Loads the venv's repair of Fast DDS's enable order (owl_fastdds_enable_order.c), if built.

    Called before rclpy's extension loads: that load binds Fast DDS's calls at once (RTLD_NOW), and
    with RTLD_GLOBAL this library's RTPSParticipantImpl::enable() comes before Fast DDS's own.
    _ctypes.dlopen, not ctypes: importing ctypes would cost every node 4-6 ms.
    """
    library = os.path.join(sys.prefix, 'lib', FASTDDS_ENABLE_ORDER)
    if os.path.exists(library):
        import _ctypes
        try:
            _ctypes.dlopen(library, os.RTLD_NOW | os.RTLD_GLOBAL)
        except OSError as error:  # rclpy still works, with upstream's order; say so once
            print(f'owl: Fast DDS enable-order repair not loaded ({error}); run make setup',
                  file=sys.stderr)


def patch_init(rclpy: Any) -> None:
    """A plain rclpy.init() of the default context gets Ctrl-C as on Humble (see above)."""
    init = rclpy.init

    @wraps(init)
    def init_with_ctrl_c_as_on_humble(*args: Any, **kwargs: Any) -> Any:
        context = kwargs.get('context')
        if (kwargs.get('signal_handler_options') is None
                and (context is None or context is rclpy.get_default_context())
                and CtrlCAsOnHumble.take_over()):
            kwargs['signal_handler_options'] = rclpy.SignalHandlerOptions.NO
        return init(*args, **kwargs)

    rclpy.init = init_with_ctrl_c_as_on_humble


def install() -> None:
    """Called by the .pth line at every start of the venv's Python; costs nothing until rclpy."""
    for hook in (RclpyImportHook, GeneratorOnFirstUse):
        if hook not in sys.meta_path:
            sys.meta_path.insert(0, hook)


class GeneratorOnFirstUse:
    """A sys.meta_path entry that gives rosidl_generator_py's code generator a loader that waits."""

    module = 'rosidl_generator_py.generate_py_impl'

    @classmethod
    def find_spec(cls, fullname: str, path: Sequence[str] | None = None,
                  target: ModuleType | None = None) -> ModuleSpec | None:
        """The generator module's spec with a LoadOnFirstUse loader; None for any other module."""
        if fullname != cls.module:
            return None
        sys.meta_path.remove(cls)
        spec = find_spec_after(cls, fullname, target, path)
        if spec is None or spec.loader is None:
            return None
        spec.loader = LoadOnFirstUse(spec.loader)  # type: ignore[assignment]  # duck-typed loader
        return spec


class LoadOnFirstUse:
    """The module's own loader, run when generate_py is called or another name is asked for."""

    def __init__(self, loader: Any) -> None:
        self.loader = loader
        self._lock = threading.RLock()

    def create_module(self, spec: ModuleSpec) -> ModuleType | None:
        """The module object as the wrapped loader makes it (None: Python's default one)."""
        return self.loader.create_module(spec)

    def exec_module(self, module: ModuleType) -> None:
        """Give module a forwarding generate_py and a module __getattr__ that load the real code.

        A load that fails (the generator's own imports) raises at that use and is tried again at
        the next one, as importing the module would.
        """
        loading = False

        def load() -> None:
            nonlocal loading
            with self._lock:
                if loading or module.__dict__.get('__getattr__') is not attribute:
                    return  # loaded already, or asked for by its own code while it loads
                loading = True
                try:
                    self.loader.exec_module(module)
                finally:
                    loading = False
                del module.__dict__['__getattr__']

        def generate_py(*args: Any, **kwargs: Any) -> Any:
            load()
            return module.generate_py(*args, **kwargs)

        def attribute(name: str) -> Any:
            if not (name.startswith('__') and name.endswith('__')):  # import asks for __path__
                load()
            try:
                return module.__dict__[name]
            except KeyError:
                raise AttributeError(f'module {module.__name__!r} has no attribute {name!r}') from None

        module.__dict__['generate_py'] = generate_py
        module.__dict__['__getattr__'] = attribute

    def __getattr__(self, name: str) -> Any:
        return getattr(self.loader, name)


def patch_executors(executors: Any) -> None:
    """Patch rclpy.executors: takes keep Ctrl-C out, the spin-until-future methods leave no wake-ups.

    A handler cut short by a Ctrl-C gives back what it claimed (Task.__call__, from rclpy.task).
    A timer cancelled after its handler was filed has no work left (_take_timer).

    Future.__del__ (rclpy.task) is patched here too, to skip the futures a Ctrl-C left half built,
    and Executor.__del__, to leave a guard condition that finalised itself first alone.
    """
    for name in TAKES:
        setattr(executors.Executor, name, keep_ctrl_c_out(getattr(executors.Executor, name)))
    executors.Executor._make_handler = file_with_claim(executors.Executor._make_handler)
    executors.Executor._take_timer = skip_cancelled(executors.Executor._take_timer)
    from rclpy.task import Future, Task
    Future.__del__ = skip_half_built(Future.__del__)  # type: ignore[method-assign]
    Task.__call__ = give_back_on_ctrl_c(Task.__call__)  # type: ignore[method-assign]
    executors.Executor.__del__ = forgive_missing_guard(executors.Executor.__del__)
    for cls in (executors.Executor, executors.SingleThreadedExecutor, executors.MultiThreadedExecutor):
        for name in SPINS_UNTIL_FUTURE:
            if name in vars(cls):
                setattr(cls, name, drop_stale_wakers(vars(cls)[name], executors.__file__))


def patch_action_client(client: Any) -> None:
    """Each ActionClient files a request's Future before the executor may handle its response."""
    action_client = client.ActionClient
    init = action_client.__init__

    @wraps(init)
    def init_with_filing_lock(self: Any, *args: Any, **kwargs: Any) -> None:
        self._owl_filing = threading.Lock()
        init(self, *args, **kwargs)

    action_client.__init__ = init_with_filing_lock
    for name in SENDS:
        setattr(action_client, name, filing_under_lock(getattr(action_client, name)))
    execute = action_client.execute

    @wraps(execute)
    async def execute_once_filed(self: Any, taken_data: Any) -> Any:
        with self._owl_filing:  # a request being sent is filed before its response is looked up
            pass
        return await execute(self, taken_data)

    action_client.execute = execute_once_filed


def filing_under_lock(send: Callable[..., Any]) -> Callable[..., Any]:
    """send, run under the client's filing lock: its Future is filed before execute() looks it up."""
    @wraps(send)
    def send_and_file(self: Any, *args: Any, **kwargs: Any) -> Any:
        with self._owl_filing:
            return send(self, *args, **kwargs)

    return send_and_file


def drop_stale_wakers(spin: Callable[..., Any], executors_file: str) -> Callable[..., Any]:
    """spin_until_future_complete (or its spin_once_), leaving none of its wake-ups behind."""
    def is_waker(callback: Any) -> bool:
        code = getattr(callback, '__code__', None)
        return code is not None and code.co_name == '<lambda>' and code.co_filename == executors_file

    @wraps(spin)
    def spin_without_leftovers(executor: Any, future: Any, *args: Any, **kwargs: Any) -> Any:
        try:
            return spin(executor, future, *args, **kwargs)
        finally:
            for callback in [c for c in getattr(future, '_callbacks', ()) if is_waker(c)]:
                future.remove_done_callback(callback)
            with executor._tasks_lock:
                executor._tasks = [(task, entity, node) for task, entity, node in executor._tasks
                                   if task.executing() or not is_waker(getattr(task, '_handler', None))]

    return spin_without_leftovers


def skip_half_built(delete: Callable[[Any], None]) -> Callable[[Any], None]:
    """Future.__del__, doing nothing for a future whose __init__ a Ctrl-C cut short.

    A Task dropped before its handler ran has its coroutine closed: nothing can resume it now.
    """
    @wraps(delete)
    def __del__(future: Any) -> None:  # named so that in_code_that_loses_exceptions knows it
        handler = vars(future).get('_handler')
        if getattr(handler, 'cr_frame', None) is not None:  # a coroutine not yet finished
            handler.close()
        if hasattr(future, '_exception_fetched'):  # set after _exception: __init__ got past both
            delete(future)

    return __del__


def forgive_missing_guard(delete: Callable[[Any], None]) -> Callable[[Any], None]:
    """Executor.__del__, quiet when its SIGINT guard condition was destroyed before it or never made."""
    from rclpy.exceptions import InvalidHandle

    @wraps(delete)
    def __del__(executor: Any) -> None:  # named so that in_code_that_loses_exceptions knows it
        if '_sigint_gc' not in vars(executor):  # a Ctrl-C cut its __init__ short
            return
        try:
            delete(executor)
        except InvalidHandle:  # the guard finalised itself first, at interpreter exit
            pass

    return __del__


def file_with_claim(make_handler: Callable[..., Any]) -> Callable[..., Any]:
    """Executor._make_handler, filing its Task whole and telling it which entity it claims."""
    @wraps(make_handler)
    def make_handler_filed_whole(executor: Any, entity: Any, *args: Any) -> Any:
        python_handler = pythons_ctrl_c()
        if python_handler is None or rclpy_handles_ctrl_c():
            task = make_handler(executor, entity, *args)
        else:
            task = hold_ctrl_c(python_handler, make_handler, executor, entity, *args)
        task._owl_claimed = entity
        return task

    return make_handler_filed_whole


def skip_cancelled(take_timer: Callable[[Any, Any], Any]) -> Callable[[Any, Any], Any]:
    """Executor._take_timer, finding no work (not an RCLError) in a timer cancelled since it was filed."""
    from rclpy.impl.implementation_singleton import rclpy_implementation

    @wraps(take_timer)
    def take_timer_unless_cancelled(executor: Any, timer: Any) -> Any:
        try:
            return take_timer(executor, timer)
        except rclpy_implementation.RCLError:  # "failed to call timer: timer is canceled"
            if timer.is_canceled():
                return None
            raise

    return take_timer_unless_cancelled


def give_back_on_ctrl_c(call: Callable[[Any], None]) -> Callable[[Any], None]:
    """Task.__call__, giving back the entity and callback group a handler claimed if a Ctrl-C ends it."""
    @wraps(call)
    def call_giving_back(task: Any) -> None:
        try:
            call(task)
        except KeyboardInterrupt:
            entity = getattr(task, '_owl_claimed', None)
            if entity is not None:
                entity._executor_event = False
                group = entity.callback_group
                if getattr(group, '_active_entity', None) is entity:
                    group.ending_execution(entity)
                task.cancel()  # else it stays "executing" in the executor's list for good
            raise

    return call_giving_back


def pythons_ctrl_c() -> Callable[[int, FrameType | None], Any] | None:
    """SIGINT's handler if a Ctrl-C raises in this thread through it (Python's default or CtrlC's)."""
    python_handler = _signal.getsignal(signal.SIGINT)  # signal.getsignal's enum lookup costs 5 us
    if (threading.current_thread() is not threading.main_thread()
            or python_handler not in (signal.default_int_handler, raise_ctrl_c)):
        return None
    return python_handler


def rclpy_handles_ctrl_c() -> bool:
    """Whether rclpy's own SIGINT handler is installed (under Python's, which it calls)."""
    return RclpyHandlerOptions.current().value in RclpyHandlerOptions.with_sigint


class RclpyHandlerOptions:
    """rclpy.signals' SignalHandlerOptions, as patch_signals finds them (compared as ints: faster)."""

    current: ClassVar[Callable[[], Any]]
    with_sigint: ClassVar[frozenset[int]]


def hold_ctrl_c(python_handler: Callable[[int, FrameType | None], Any], call: Callable[..., Any],
                *args: Any) -> Any:
    """call(*args), with a Ctrl-C that lands inside it given to python_handler as it returns.

    Not while rclpy's handler is installed: signal.signal would replace it in the kernel too.
    """
    if python_handler is raise_ctrl_c:  # ours reads a flag: cheaper than two signal.signal (15 us)
        outer = CtrlCAsOnHumble.holding
        CtrlCAsOnHumble.holding = True
        try:
            result = call(*args)
        finally:
            CtrlCAsOnHumble.holding = outer
        if CtrlCAsOnHumble.held and not outer:
            CtrlCAsOnHumble.held = False
            raise_ctrl_c(signal.SIGINT, None)
        return result
    held: list[int] = []
    signal.signal(signal.SIGINT, lambda signum, frame: held.append(signum))
    try:
        result = call(*args)
    finally:
        signal.signal(signal.SIGINT, python_handler)
    if held:
        python_handler(signal.SIGINT, None)
    return result


def keep_ctrl_c_out(take: Callable[..., Any]) -> Callable[..., Any]:
    """take, with a Ctrl-C that lands inside it raised as KeyboardInterrupt (see the module's text)."""
    @wraps(take)
    def take_keeping_ctrl_c_out(executor: Any, entity: Any) -> Any:
        python_handler = pythons_ctrl_c()
        if python_handler is None:
            return take(executor, entity)
        if rclpy_handles_ctrl_c():
            try:
                return take(executor, entity)
            except Exception as error:
                if was_ctrl_c(error, executor.context):
                    raise KeyboardInterrupt from None
                raise
        return hold_ctrl_c(python_handler, take, executor, entity)

    return take_keeping_ctrl_c_out


def was_ctrl_c(error: Exception, context: Any) -> bool:
    """Whether pybind11 made error of a KeyboardInterrupt raised inside a take."""
    if isinstance(error.__cause__, KeyboardInterrupt):
        return True
    return isinstance(error, RuntimeError) and CONVERSION_ERROR in str(error) and shut_down_soon(context)


def shut_down_soon(context: Any) -> bool:
    """Whether the context goes down within SHUTDOWN_GRACE seconds (looked at every 10 ms)."""
    deadline = time.monotonic() + SHUTDOWN_GRACE
    while context.ok():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.01)
    return True
