"""Scenes: a built-in, a file, TOML text or a dict, with ``path=value`` overrides.

A :class:`Scene` is a recipe (its source name, its TOML text and the overrides), so it pickles
to the workers of a process pool or a Dask cluster; the validated C++ scene is built on first
use and cached.
"""

from __future__ import annotations

import json
import math
import os
import tomllib
from collections.abc import Iterable, Mapping
from typing import Any

from . import _geardyn  # type: ignore[attr-defined]

__all__ = ["Scene", "builtin_scenes", "to_toml", "toml_value"]


def builtin_scenes() -> list[str]:
    """The names of the built-in scenes (load one with ``Scene.builtin(name)``)."""
    return list(_geardyn.builtin_scene_names())


def toml_value(value: Any) -> str:
    """``value`` as a TOML value: bool, int, float, str, or a list of them.

    Raises:
        InputError: for a non-finite float, or a type TOML cannot hold.
    """
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise _geardyn.InputError(f"{value!r}: not a finite number")
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if hasattr(value, "item"):  # a numpy scalar
        return toml_value(value.item())
    raise _geardyn.InputError(f"{value!r}: a {type(value).__name__} is not a TOML value")


def _is_table_array(value: Any) -> bool:
    return isinstance(value, (list, tuple)) and len(value) > 0 and all(
        isinstance(v, Mapping) for v in value)


def to_toml(data: Mapping[str, Any]) -> str:
    """A dict (the shape ``tomllib.loads`` returns) as TOML text."""
    lines: list[str] = []

    def table(prefix: str, d: Mapping[str, Any]) -> None:
        for key, value in d.items():
            if not isinstance(value, Mapping) and not _is_table_array(value):
                lines.append(f"{_key(key)} = {toml_value(value)}")
        for key, value in d.items():
            name = f"{prefix}.{_key(key)}" if prefix else _key(key)
            if isinstance(value, Mapping):
                lines.append("")
                lines.append(f"[{name}]")
                table(name, value)
            elif _is_table_array(value):
                for element in value:
                    lines.append("")
                    lines.append(f"[[{name}]]")
                    table(name, element)

    table("", data)
    return "\n".join(lines) + "\n"


def _key(key: str) -> str:
    bare = key.replace("_", "").replace("-", "").isalnum() and key.isascii()
    return key if bare else json.dumps(key)


def _override_strings(overrides: Mapping[str, Any] | Iterable[str] | None) -> list[str]:
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        return [f"{path}={toml_value(value)}" for path, value in overrides.items()]
    if isinstance(overrides, str):
        return [overrides]
    return [str(o) for o in overrides]


class Scene:
    """A gear-system scene (docs/scene-format.md) with overrides.

    Make one with :meth:`builtin`, :meth:`from_file`, :meth:`from_toml`, :meth:`from_dict` or
    :meth:`load`; :meth:`with_overrides` gives a variant. Reading and validation errors raise
    :class:`geardyn.SceneError` with the C++ reader's message (``file:line: key: reason``).
    """

    def __init__(self, source: str, text: str | None = None,
                 overrides: Mapping[str, Any] | Iterable[str] | None = None) -> None:
        """``source`` is ``builtin:NAME`` or the name errors use; ``text`` the TOML text (None:
        read ``source`` as a built-in or a file when the scene is first used)."""
        self._source = str(source)
        self._text = text
        self._overrides = tuple(_override_strings(overrides))
        self._handle: Any = None

    # ---- constructors ------------------------------------------------------------------------
    @classmethod
    def builtin(cls, name: str, overrides: Mapping[str, Any] | Iterable[str] | None = None
                ) -> Scene:
        """The built-in scene ``name`` (``builtin_scenes()`` lists them)."""
        name = name.removeprefix("builtin:")
        scene = cls("builtin:" + name, None, overrides)
        scene.handle()  # unknown names fail here, with the reader's message
        return scene

    @classmethod
    def from_file(cls, path: str | os.PathLike[str],
                  overrides: Mapping[str, Any] | Iterable[str] | None = None) -> Scene:
        """A scene file; its text is kept, so workers on other machines need not see the file."""
        path = os.fspath(path)
        _geardyn.load_scene(path, [])  # the reader's own errors for a missing or invalid file
        with open(path, encoding="utf-8") as f:
            return cls(path, f.read(), overrides)

    @classmethod
    def from_toml(cls, text: str, name: str = "<string>",
                  overrides: Mapping[str, Any] | Iterable[str] | None = None) -> Scene:
        """TOML text; ``name`` is what error messages call it."""
        return cls(name, text, overrides)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], name: str = "<dict>",
                  overrides: Mapping[str, Any] | Iterable[str] | None = None) -> Scene:
        """A dict of the scene file's tables (the shape ``tomllib.loads`` returns)."""
        return cls(name, to_toml(data), overrides)

    @classmethod
    def load(cls, spec: str | os.PathLike[str] | Scene,
             overrides: Mapping[str, Any] | Iterable[str] | None = None) -> Scene:
        """``builtin:NAME``, a file path, or a Scene (returned with the overrides added)."""
        if isinstance(spec, Scene):
            return spec.with_overrides(overrides) if overrides else spec
        spec = os.fspath(spec)
        if spec.startswith("builtin:"):
            return cls.builtin(spec, overrides)
        return cls.from_file(spec, overrides)

    # ---- variants ------------------------------------------------------------------------------
    def with_overrides(self, overrides: Mapping[str, Any] | Iterable[str] | None) -> Scene:
        """A copy with more overrides (applied after this scene's, in order).

        ``{"gear.pinion.teeth": 23, "mesh.pinion-wheel.model": "slices"}`` or
        ``["gear.pinion.teeth=23"]``.
        """
        return Scene(self._source, self._text, self._overrides + tuple(_override_strings(overrides)))

    # ---- properties ----------------------------------------------------------------------------
    @property
    def source(self) -> str:
        """``builtin:NAME``, the file path, or the name given to a text or dict scene."""
        return self._source

    @property
    def overrides(self) -> tuple[str, ...]:
        """The ``path=value`` overrides, in the order they apply."""
        return self._overrides

    @property
    def text(self) -> str:
        """The TOML text before the overrides (a built-in's text for built-ins)."""
        if self._text is not None:
            return self._text
        text = _geardyn.builtin_scene_text(self._source.removeprefix("builtin:"))
        if text is None:
            raise _geardyn.InputError(f"{self._source}: no text (not a built-in scene)")
        return text

    def to_dict(self) -> dict[str, Any]:
        """The scene's tables before the overrides (``tomllib.loads`` of :attr:`text`)."""
        return tomllib.loads(self.text)

    @property
    def title(self) -> str:
        """The scene's free-text title (may be empty)."""
        return self.handle().title

    @property
    def mesh_frequency_hz(self) -> float:
        """The first mesh's tooth-mesh frequency at the operating speed [Hz] (an oscillator
        scene: its frequency ratio)."""
        return self.handle().mesh_frequency_hz

    @property
    def mesh_names(self) -> list[str]:
        """The meshes' names, in scene order (the keys of the results' per-mesh dicts)."""
        return list(self.handle().mesh_names)

    def handle(self) -> Any:
        """The validated C++ scene (parsed on first use, then cached)."""
        if self._handle is None:
            if self._text is None:
                self._handle = _geardyn.load_scene(self._source, list(self._overrides))
            else:
                self._handle = _geardyn.parse_scene(self._text, self._source,
                                                    list(self._overrides))
        return self._handle

    def __getstate__(self) -> dict[str, Any]:
        """The recipe only: the C++ scene is parsed again where it is unpickled."""
        return {"source": self._source, "text": self._text, "overrides": self._overrides}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self._source = state["source"]
        self._text = state["text"]
        self._overrides = tuple(state["overrides"])
        self._handle = None

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Scene) and self.__getstate__() == other.__getstate__()

    def __hash__(self) -> int:
        return hash((self._source, self._text, self._overrides))

    def __repr__(self) -> str:
        extra = f", overrides={list(self._overrides)}" if self._overrides else ""
        return f"Scene({self._source!r}{extra})"
