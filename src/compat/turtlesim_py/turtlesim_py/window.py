"""An optional Tk window showing the canvas, titled TurtleSim like upstream's Qt frame.

It has no thread or event loop of its own: the node opens it, pumps Tk and closes it from its
16 ms tick, much as upstream runs ROS callbacks from the Qt timer. So every Tk call happens on
the tick's thread.
"""

from __future__ import annotations

import tkinter
from collections.abc import Callable

from PIL import Image, ImageTk

from turtlesim_py import world


class CanvasWindow:
    """The TurtleSim window, showing the canvas; on_close runs when the user closes it."""

    def __init__(self, on_close: Callable[[], None]) -> None:
        """Raises tkinter.TclError when no display can be opened."""
        self._root = tkinter.Tk()
        self._root.title('TurtleSim')
        self._root.resizable(False, False)
        # One photo image, repainted in place: a new one per frame costs several times more.
        self._photo = ImageTk.PhotoImage(Image.new('RGB', (world.CANVAS_PX, world.CANVAS_PX)))
        self._label = tkinter.Label(self._root, borderwidth=0, image=self._photo)
        self._label.pack()
        self._root.protocol('WM_DELETE_WINDOW', on_close)

    def show(self, frame: Image.Image) -> None:
        """Show a rendered frame, repainting the window's one image in place."""
        self._photo.paste(frame)

    def pump(self) -> None:
        """Handle pending window events and redraws, without blocking."""
        self._root.update()

    def held_keys(self) -> frozenset[str]:
        """Always none: like upstream's window, this one sends the simulator no keys."""
        return frozenset()

    def close(self) -> None:
        """Destroy the window; it cannot be used again."""
        self._root.destroy()
