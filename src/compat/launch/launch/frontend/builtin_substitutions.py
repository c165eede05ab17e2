"""The `$(...)` names of launch's own substitutions."""

from __future__ import annotations

from typing import Any

from launch import substitutions as subs
from launch.frontend.expose import expose_substitution

Args = list[Any]


@expose_substitution('var', 1, 2)
def _var(name: Args, default: Args | None = None) -> subs.LaunchConfiguration:
    return subs.LaunchConfiguration(name, default=default)


@expose_substitution('env', 1, 2)
def _env(name: Args, default: Args | None = None) -> subs.EnvironmentVariable:
    return subs.EnvironmentVariable(name, default_value=default)


@expose_substitution('find-exec', 1)
def _find_exec(name: Args) -> subs.FindExecutable:
    return subs.FindExecutable(name=name)


@expose_substitution('eval', 1, 2)
def _eval(expression: Args, modules: Args | None = None) -> subs.PythonExpression:
    if modules is None:
        return subs.PythonExpression(expression)
    names = ''.join(getattr(s, 'text', '') for s in modules)
    return subs.PythonExpression(expression, [m.strip() for m in names.split(',') if m.strip()])


@expose_substitution('command', 1, 2)
def _command(command: Args, on_stderr: Args | None = None) -> subs.Command:
    return subs.Command(command, on_stderr=on_stderr or 'fail')


@expose_substitution('anon', 1)
def _anon(name: Args) -> subs.AnonName:
    return subs.AnonName(name)


@expose_substitution('dirname', 0)
def _dirname() -> subs.ThisLaunchFileDir:
    return subs.ThisLaunchFileDir()


@expose_substitution('filename', 0)
def _filename() -> subs.ThisLaunchFile:
    return subs.ThisLaunchFile()


@expose_substitution('not', 1)
def _not(value: Args) -> subs.NotSubstitution:
    return subs.NotSubstitution(value)


@expose_substitution('and', 2)
def _and(left: Args, right: Args) -> subs.AndSubstitution:
    return subs.AndSubstitution(left, right)


@expose_substitution('or', 2)
def _or(left: Args, right: Args) -> subs.OrSubstitution:
    return subs.OrSubstitution(left, right)


@expose_substitution('any', 1, 64)
def _any(*values: Args) -> subs.AnySubstitution:
    return subs.AnySubstitution(*values)


@expose_substitution('all', 1, 64)
def _all(*values: Args) -> subs.AllSubstitution:
    return subs.AllSubstitution(*values)


@expose_substitution('equals', 2)
def _equals(left: Args, right: Args) -> subs.EqualsSubstitution:
    return subs.EqualsSubstitution(left, right)


@expose_substitution('not-equals', 2)
def _not_equals(left: Args, right: Args) -> subs.NotEqualsSubstitution:
    return subs.NotEqualsSubstitution(left, right)


@expose_substitution('if', 2, 3)
def _if(condition: Args, if_value: Args, else_value: Args | None = None) -> subs.IfElseSubstitution:
    return subs.IfElseSubstitution(condition, if_value, else_value or '')


@expose_substitution('file-content', 1)
def _file_content(path: Args) -> subs.FileContent:
    return subs.FileContent(path)


@expose_substitution('launch_log_dir', 0)
def _launch_log_dir() -> subs.LaunchLogDir:
    return subs.LaunchLogDir()


expose_substitution('log_dir', 0)(_launch_log_dir)
