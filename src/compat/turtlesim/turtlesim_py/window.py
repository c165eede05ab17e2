"""An optional Tk window showing the canvas, titled TurtleSim like upstream's Qt frame.

It only displays the frames the node renders; the simulation never depends on it. Tk lives in its
own thread (all Tk calls stay there) so the node keeps the main thread and its Ctrl-C handling.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING

import rclpy

from turtlesim_py import world

if TYPE_CHECKING:
    from turtlesim_py.turtlesim_node import TurtlesimNode

REFRESH_MS = world.TICK_MS


class CanvasWindow:
    def __init__(self, node: TurtlesimNode) -> None:
        self._node = node
        self._closing = threading.Event()
        self._thread = threading.Thread(target=self._run, name='turtlesim-window', daemon=True)
        self._thread.start()

    def close(self) -> None:
        self._closing.set()
        self._thread.join(2.0)

    def _run(self) -> None:
        import tkinter

        from PIL import ImageTk

        try:
            root = tkinter.Tk()
        except tkinter.TclError as error:
            self._node.get_logger().warning(f'No window ({error}); running headless')
            self._node.want_frames = False
            return
        root.title('TurtleSim')
        root.resizable(False, False)
        label = tkinter.Label(root, borderwidth=0, width=world.CANVAS_PX, height=world.CANVAS_PX)
        label.pack()
        shown = {'frame': None, 'photo': None}

        def refresh() -> None:
            if self._closing.is_set():
                root.destroy()
                return
            frame = self._node.frame
            if frame is not None and frame is not shown['frame']:
                shown['frame'], shown['photo'] = frame, ImageTk.PhotoImage(frame)
                label.configure(image=shown['photo'])
            root.after(REFRESH_MS, refresh)

        def closed_by_user() -> None:
            # Closing the window ends the process, as upstream's does.
            root.destroy()
            rclpy.try_shutdown(context=self._node.context)

        root.protocol('WM_DELETE_WINDOW', closed_by_user)
        root.after(0, refresh)
        root.mainloop()
