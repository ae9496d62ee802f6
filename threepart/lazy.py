"""A package's public names loaded on first use (PEP 562): one home for ``threepart``, ``threepart.reports``
and ``threepart.reports.verify``.

Names
-----
lazy_names -- the ``__getattr__`` and ``__dir__`` of a package whose names live in its modules; its names
              stay those values when a submodule of the same name loads
"""
from __future__ import annotations

import importlib
import sys
import types
from typing import Any, Callable

__all__ = ["lazy_names"]


def lazy_names(package: str, homes: dict[str, str], subpackages: tuple[str, ...] = ()
               ) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``(__getattr__, __dir__)`` for ``package``: each name of ``homes`` from its module, on first use.

    ``homes`` maps a public name to the module that defines it, relative to ``package``; the
    value found is kept as the package's attribute, so a name is looked up once. A name of
    ``subpackages`` is that subpackage, imported. Importing the package itself loads nothing.

    Importing a submodule binds it as its package's attribute: ``threepart.reports.compare``
    would become the module :mod:`reports.compare` instead of its function ``compare``, as an
    eager ``from .compare import compare`` would have rebound it. The package's module class
    keeps a name of ``homes`` from being bound to a module.
    """
    class Package(types.ModuleType):
        def __setattr__(self, name: str, value: Any) -> None:
            if name in homes and isinstance(value, types.ModuleType):
                return
            super().__setattr__(name, value)

    sys.modules[package].__class__ = Package

    def __getattr__(name: str) -> Any:
        if name in homes:
            value = getattr(importlib.import_module(f".{homes[name]}", package), name)
            setattr(sys.modules[package], name, value)
            return value
        if name in subpackages:
            return importlib.import_module(f".{name}", package)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return sorted({*vars(sys.modules[package]), *homes, *subpackages})

    return __getattr__, __dir__
