"""The `$(name arg ...)` syntax of XML and YAML attribute values, as a list of substitutions.

Literal text and `$(...)` pieces, nestable; arguments are separated by spaces and may be single-
or double-quoted (quotes may hold substitutions too); a backslash escapes the next character.
"""

from __future__ import annotations

import re
from typing import Any

from launch.frontend import builtin_substitutions  # noqa: F401  (registers launch's `$(...)` names)
from launch.frontend.expose import load_launch_extensions, substitution_parse_methods
from launch.substitution import Substitution
from launch.substitutions.text_substitution import TextSubstitution

_IDENTIFIER = re.compile(r'[A-Za-z][A-Za-z0-9_-]*')


class _Reader:
    def __init__(self, text: str) -> None:
        self.text = text
        self.pos = 0

    def template(self, stop: str) -> list[Substitution]:
        """Text and substitutions up to (not including) a character of stop, or the end."""
        parts: list[Substitution] = []
        literal: list[str] = []

        def flush() -> None:
            if literal:
                parts.append(TextSubstitution(text=''.join(literal)))
                literal.clear()

        while self.pos < len(self.text):
            char = self.text[self.pos]
            if self.text.startswith('$(', self.pos):
                flush()
                parts.append(self.substitution())
            elif char in stop:
                break
            elif char == '\\' and self.pos + 1 < len(self.text):
                literal.append(self.text[self.pos + 1])
                self.pos += 2
            else:
                literal.append(char)
                self.pos += 1
        flush()
        return parts

    def substitution(self) -> Substitution:
        start = self.pos
        self.pos += 2
        match = _IDENTIFIER.match(self.text, self.pos)
        if match is None:
            raise ValueError(f"invalid substitution at character {start + 1} of '{self.text}': "
                             "expected a name after '$('")
        name = match.group()
        self.pos = match.end()
        args: list[list[Substitution]] = []
        while True:
            while self.pos < len(self.text) and self.text[self.pos] == ' ':
                self.pos += 1
            if self.pos >= len(self.text):
                raise ValueError(f"unterminated substitution '$({name}' in '{self.text}'")
            if self.text[self.pos] == ')':
                self.pos += 1
                break
            args.append(self.argument())
        make = substitution_parse_methods.get(name)
        if make is None:
            raise ValueError(f'Unknown substitution: {name}')
        return make(args)

    def argument(self) -> list[Substitution]:
        parts: list[Substitution] = []
        while self.pos < len(self.text) and self.text[self.pos] not in ' )':
            quote = self.text[self.pos]
            if quote in '\'"':
                self.pos += 1
                parts += self.template(quote)
                if self.pos >= len(self.text):
                    raise ValueError(f"unterminated quote {quote} in '{self.text}'")
                self.pos += 1
            else:
                parts += self.template(' )\'"')
        return parts


def parse_substitution(text: str) -> list[Substitution]:
    """The substitutions of one attribute value ('' gives [TextSubstitution('')]).

    The names of the installed launch extensions (launch_ros's `$(find-pkg-share ...)`...) are
    known too: their modules are imported first, once.
    """
    load_launch_extensions()
    parts = _Reader(text).template('')
    return parts or [TextSubstitution(text='')]


def parse_if_substitutions(value: Any) -> Any:
    """A typed attribute value with its text parsed: what normalize_typed_substitution accepts.

    Text holding a `$(...)` becomes a substitution list, plain text stays a str, other scalars
    stay as they are, and a list is read item by item; its items must then be of one type.
    """
    kinds: set[type] = set()

    def parse_item(item: Any) -> Any:
        if not isinstance(item, str):
            kinds.add(type(item))
            return item
        parts = parse_substitution(item)
        if len(parts) == 1 and isinstance(parts[0], TextSubstitution):
            kinds.add(str)
            return parts[0].text
        return parts

    result = [parse_item(item) for item in value] if isinstance(value, list) else parse_item(value)
    if len(kinds) > 1:
        raise ValueError(f'the list {value!r} mixes values of several types: '
                         f'{", ".join(sorted(kind.__name__ for kind in kinds))}')
    return result
