"""An optional Tk window showing the canvas, titled TurtleSim like upstream's Qt frame.

It has no thread or event loop of its own: the node pumps Tk from its 16 ms tick, much as
upstream runs ROS callbacks from the Qt timer. So every Tk call happens on the node's thread.
"""

from __future__ import annotations

import tkinter
from collections.abc import Callable

from PIL import Image, ImageTk

from turtlesim_py import world


class CanvasWindow:
    def __init__(self, on_close: Callable[[], None]) -> None:
        """Raises tkinter.TclError when no display can be opened."""
        self._root = tkinter.Tk()
        self._root.title('TurtleSim')
        self._root.resizable(False, False)
        self._label = tkinter.Label(self._root, borderwidth=0)
        self._label.pack()
        self._photo: ImageTk.PhotoImage | None = None
        self._root.protocol('WM_DELETE_WINDOW', on_close)
        self.show(Image.new('RGB', (world.CANVAS_PX, world.CANVAS_PX)))

    def show(self, frame: Image.Image) -> None:
        self._photo = ImageTk.PhotoImage(frame)
        self._label.configure(image=self._photo)

    def pump(self) -> None:
        """Handle pending window events and redraws, without blocking."""
        self._root.update()

    def close(self) -> None:
        self._photo = None
        self._root.destroy()
