"""The exceptions seasim raises (the C++ core's InputError, DeviceError and RuntimeError)."""

from __future__ import annotations


class SceneError(ValueError):
    """Bad input in a scene, a scene dict or an override.

    The message reads like the command line's: ``FILE:LINE: key 'KEY': message`` for a file, and
    ``<dict>: key 'camera.width': ...`` or ``<overrides>: key ...`` where there is no line.
    """

    file: str | None = None  #: the scene or job file; None for a dict or an override
    line: int | None = None  #: the line in that file; None for a dict or an override
    key: str | None = None  #: the dotted key (a dict's path to the value), when the error has one


class DeviceError(RuntimeError):
    """No OpenCL device (or platform), a device that cannot hold the render, a kernel build or OpenCL failure."""


class RenderError(RuntimeError):
    """Any other failure of a render, reference or job: NaN/Inf from the kernels, I/O, a missing data file."""
