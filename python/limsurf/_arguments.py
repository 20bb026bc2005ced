"""Refused calls explained by argument.

pybind11 refuses a call whose arguments do not convert with a message that prints the signature and
the types it was invoked with, and leaves the reader to find the culprit. The wrappers here catch
that one refusal and raise a TypeError that names the argument and what was wrong with it:

    volume(): argument 'mesh' must be limsurf.Mesh, got numpy.ndarray (3, 3) float64
    (make one with limsurf.Mesh(V, F) or limsurf.read_mesh(path))
        volume(mesh: limsurf.Mesh, scheme: str, *, gradient: bool = False, ...)

The checks mirror pybind11's own conversions (an int is not accepted for a str, a float is not an
int, a bool takes anything with a truth value but a str or a sequence). Where the checks find nothing
wrong (an annotation they cannot judge), pybind11's message passes unchanged, so an explanation is
never worse than the original. Every other error passes untouched; a call that converts costs one
Python frame.
"""
from __future__ import annotations

import collections.abc
import functools
import operator
import os
import re

_REFUSAL = re.compile(r"^(\w+)\(\): incompatible (function|constructor) arguments\.")
_OVERLOAD = re.compile(r"^\s+\d+\. ([\w.]*)\((.*)\)(?: -> .*)?$")
_PACKAGE_PREFIX = "limsurf._limsurf."


def explained(function, classes):
    """`function` wrapped so that pybind11's refusal names the argument; `classes` maps the module's
    class names to the classes, for annotations such as limsurf._limsurf.Mesh."""

    @functools.wraps(function)
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except TypeError as refusal:
            message = _explain(str(refusal), args, kwargs, classes)
            if message is None:
                raise
            raise TypeError(message) from None

    return call


def explain_methods(cls, classes):
    """Every method of the pybind11 class `cls` (its constructor included) wrapped by `explained`."""
    for name, attribute in list(vars(cls).items()):
        if name != "__init__" and (name.startswith("_") or isinstance(attribute, property)):
            continue
        if type(attribute).__name__ != "instancemethod":
            continue
        setattr(cls, name, explained(getattr(cls, name), classes))


def _explain(text, args, kwargs, classes):
    refusal = _REFUSAL.match(text)
    if refusal is None:
        return None
    name, kind = refusal.groups()
    matches = [m for m in map(_OVERLOAD.match, text.splitlines()) if m]
    if not matches:
        return None
    if kind == "constructor":  # "limsurf._limsurf.Mesh(V: handle, ...)": no self, the class names the call
        args = args[1:]
        name = matches[0].group(1).split(".")[-1] or name
    overloads = [m.group(2) for m in matches]
    problems = []
    for signature in overloads:
        problem = _problem(_parameters(signature), args, kwargs, classes)
        if problem is None:
            return None  # nothing found wrong with this overload: pybind11 knows better
        problems.append(problem)
    if len(problems) == 1:
        return f"{name}(): {problems[0]}\n    {name}({_readable(overloads[0])})"
    lines = [f"{name}(): no overload takes these arguments:"]
    for signature, problem in zip(overloads, problems):
        lines.append(f"    {name}({_readable(signature)}): {problem}")
    return "\n".join(lines)


def docstring_signatures(doc):
    """The parameter lists of the overloads a pybind11 docstring shows ("name(a: int, ...) -> T", or
    "Overloaded function." and numbered lines), each as _parameters gives it; None for one it cannot read."""
    lines = (doc or "").splitlines()
    if lines[1:2] == ["Overloaded function."]:
        lines = [line.split(". ", 1)[1] for line in lines if re.match(r"^\d+\. [\w.]*\(", line)]
    else:
        lines = lines[:1]
    out = []
    for line in lines:
        match = re.match(r"^[\w.]*\((.*)\)(?: -> .*)?$", line.strip())
        out.append(_parameters(match.group(1)) if match else None)
    return out


def _parameters(signature):
    """[(name, annotation, has_default, keyword_only)] of one overload's parameter list."""
    parameters, keyword_only = [], False
    for item in _split_top_level(signature):
        item = item.strip()
        if item == "*":
            keyword_only = True
            continue
        if item.startswith("*"):
            return None  # *args or **kwargs: anything binds
        head, has_default = item.split(" = ", 1)[0], " = " in item
        parameter, _, annotation = head.partition(": ")
        parameters.append((parameter.strip(), annotation.strip(), has_default, keyword_only))
    return parameters


def _split_top_level(text):
    """`text` split at the commas outside brackets and quotes."""
    items, depth, quote, start = [], 0, None, 0
    for i, c in enumerate(text):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            items.append(text[start:i])
            start = i + 1
    if text[start:].strip():
        items.append(text[start:])
    return items


def _problem(parameters, args, kwargs, classes):
    """What keeps (args, kwargs) from binding to `parameters`, as a phrase, or None if nothing."""
    if parameters is None:
        return None
    positional = [p for p in parameters if not p[3]]
    if len(args) > len(positional):
        return (f"takes at most {len(positional)} positional arguments ({', '.join(p[0] for p in positional)}),"
                f" got {len(args)}")
    names = [p[0] for p in parameters]
    for key in kwargs:
        if key not in names:
            return f"unexpected keyword argument '{key}' (it takes: {', '.join(names)})"
    given = {p[0]: value for p, value in zip(positional, args)}
    for key, value in kwargs.items():
        if key in given:
            return f"argument '{key}' given twice, by position and by keyword"
        given[key] = value
    for parameter, annotation, has_default, _ in parameters:
        if parameter not in given:
            if not has_default:
                return f"missing argument '{parameter}'"
            continue
        mismatch = _mismatch(annotation, given[parameter], classes)
        if mismatch is not None:
            where, expected = mismatch
            return _must_be(parameter + where, expected, given[parameter], where, annotation)
    return None


def _must_be(argument, expected, value, where, annotation):
    shown = value
    if where:  # an element of a list: show the element
        for index in re.findall(r"\[(\d+)\]", where):
            shown = shown[int(index)]
    phrase = f"argument '{argument}' must be {expected}, got {_describe(shown)}"
    if _readable(annotation) == "limsurf.Mesh" and not where:
        phrase += " (make one with limsurf.Mesh(V, F) or limsurf.read_mesh(path))"
    if annotation == "os.PathLike" and _has_nul(value):
        phrase += " (a path cannot hold a NUL character)"
    return phrase


def _has_nul(value):
    try:
        path = os.fspath(value)
    except TypeError:
        return False
    return ("\0" if isinstance(path, str) else b"\0") in path


def _mismatch(annotation, value, classes):
    """None if `value` may convert to `annotation` (or the annotation cannot be judged), else
    (where, expected): the element path ('' or '[3]') and the expected type in words."""
    verdict = _fits(annotation, value, classes)
    if verdict is True or verdict is None:
        return None
    if isinstance(verdict, tuple):
        return verdict
    return "", _readable(annotation)


def _fits(annotation, value, classes):
    """True, None (cannot tell), False, or (element path, expected) for a list element that does not fit."""
    annotation = annotation.strip()
    simple = {
        "handle": lambda v: True,
        "object": lambda v: True,
        "str": lambda v: isinstance(v, str),
        "os.PathLike": lambda v: isinstance(v, (str, bytes, os.PathLike)) and not _has_nul(v),
        "function": callable,
        "sequence": lambda v: isinstance(v, collections.abc.Sequence) or _is_sequence(v),
        "dict": lambda v: isinstance(v, collections.abc.Mapping),
        "int": _is_integer,
        "float": lambda v: not isinstance(v, (str, bytes)) and (hasattr(type(v), "__float__") or _is_integer(v)),
        "bool": lambda v: v is None or (not isinstance(v, (str, bytes, collections.abc.Sequence))
                                        and hasattr(type(v), "__bool__")),
    }
    if annotation in simple:
        return simple[annotation](value)
    outer, inner = _generic(annotation)
    if outer == "Optional":
        return True if value is None else _fits(inner[0], value, classes)
    if outer == "Union":
        verdicts = [_fits(a, value, classes) for a in inner]
        return True if any(v is True for v in verdicts) else (None if None in verdicts else False)
    if outer in ("List", "Sequence", "list"):
        return _is_sequence(value) and _elements_fit([inner[0]] * len(value), value, classes)
    if outer in ("Tuple", "tuple"):
        return _is_sequence(value) and len(value) == len(inner) and _elements_fit(inner, value, classes)
    if outer in ("Dict", "dict"):
        return isinstance(value, collections.abc.Mapping)
    if outer == "Callable" or annotation == "Callable":
        return callable(value)
    short = annotation[len(_PACKAGE_PREFIX):] if annotation.startswith(_PACKAGE_PREFIX) else annotation
    if short in classes:
        return isinstance(value, classes[short])
    return None


def _elements_fit(annotations, elements, classes):
    """True, or (element path, expected) for the first element that does not fit its annotation."""
    for index, (annotation, element) in enumerate(zip(annotations, elements)):
        verdict = _fits(annotation, element, classes)
        if verdict is False:
            return f"[{index}]", _readable(annotation)
        if isinstance(verdict, tuple):
            return f"[{index}]{verdict[0]}", verdict[1]
    return True


def _generic(annotation):
    """('List', ['int']) for 'List[int]'; (None, []) for a plain name."""
    match = re.match(r"^([\w.]+)\[(.*)\]$", annotation)
    if match is None:
        return None, []
    return match.group(1).split(".")[-1], [item.strip() for item in _split_top_level(match.group(2))]


def _is_integer(value):
    if isinstance(value, float):
        return False
    try:
        operator.index(value)
    except TypeError:
        return False
    return True


def _is_sequence(value):
    return isinstance(value, collections.abc.Sequence) and not isinstance(value, (str, bytes)) or (
        type(value).__name__ == "ndarray" and getattr(value, "ndim", 0) > 0)


def _describe(value):
    kind = type(value)
    name = kind.__name__ if kind.__module__ == "builtins" else f"{kind.__module__}.{kind.__name__}"
    if name.startswith(_PACKAGE_PREFIX):
        name = "limsurf." + name[len(_PACKAGE_PREFIX):]
    if hasattr(value, "shape") and hasattr(value, "dtype"):
        return f"{name} {tuple(value.shape)} {value.dtype}"
    if isinstance(value, (str, int, float, bytes)) or value is None:
        text = repr(value)
        return f"{name} {text if len(text) <= 40 else text[:37] + '...'}"
    return name


def _readable(text):
    return text.replace(_PACKAGE_PREFIX, "limsurf.")
