"""InvalidLaunchFileError: no loader could read a launch file."""

from __future__ import annotations


class InvalidLaunchFileError(Exception):
    """No loader could read the file; the message lists what each loader said."""

    def __init__(self, extension: str = '', *, likely_errors: list[Exception] | None = None) -> None:
        errors = likely_errors or []
        if not errors:
            message = 'The launch file may have a syntax error, or its format is unknown'
        else:
            several = 'multiple exceptions' if len(errors) > 1 else 'exception'
            lines = [f'Caught {several} when trying to load file of format [{extension}]:']
            lines += [f' - {type(error).__name__}: {error}' for error in errors]
            message = '\n'.join(lines)
        super().__init__(message)
