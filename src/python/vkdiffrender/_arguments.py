"""One-line TypeErrors for calls into the extension that pybind11 cannot match.

pybind11 answers a misspelt keyword or an argument of the wrong type with several lines:
every signature of the function and every argument given, without naming the one that
does not fit. `named_argument_errors` wraps a bound function so that such a call raises
one line naming it instead, as Python's own functions do. The signature comes from the
first line of the docstring pybind11 writes.
"""
import difflib
import functools
import os
import re

_SIGNATURE = re.compile(r"^(?P<name>\w+)\((?P<parameters>.*)\)( -> .*)?$")


def _split_top_level(text):
    """Splits the parameter list at the commas outside brackets (List[str] has none)."""
    parts, depth, start = [], 0, 0
    for i, char in enumerate(text):
        if char in "[(":
            depth += 1
        elif char in "])":
            depth -= 1
        elif char == "," and depth == 0:
            parts.append(text[start:i].strip())
            start = i + 1
    if text[start:].strip():
        parts.append(text[start:].strip())
    return parts


class _Signature:
    def __init__(self, docstring, name):
        match = _SIGNATURE.match(docstring.partition("\n")[0] if docstring else "")
        if not match:
            raise ValueError("no pybind11 signature in the docstring")
        self.name = name or match["name"]
        self.text = match["parameters"]
        self.method = False
        self.positional, self.keyword_only, self.required, self.types = [], [], set(), {}
        keyword_only = False
        for parameter in _split_top_level(self.text):
            if parameter == "*":
                keyword_only = True
                continue
            parameter_name, _, rest = parameter.partition(":")
            annotation, has_default, _ = rest.partition("=")
            parameter_name = parameter_name.strip()
            if parameter_name == "self":
                self.method = True
                continue
            (self.keyword_only if keyword_only else self.positional).append(parameter_name)
            self.types[parameter_name] = annotation.strip()
            if not has_default:
                self.required.add(parameter_name)

    def problem(self, args, kwargs):
        """What does not fit, in one line; None where the names fit and a value's type is at fault
        in a way the annotation does not tell."""
        names = self.positional + self.keyword_only
        for keyword in kwargs:
            if keyword not in names:
                close = difflib.get_close_matches(keyword, names, n=1)
                hint = f" (did you mean '{close[0]}'?)" if close else f" (it takes {', '.join(names) or 'none'})"
                return f"{self.name}() got an unexpected keyword argument '{keyword}'{hint}"
        if len(args) > len(self.positional):
            return (f"{self.name}() takes {len(self.positional)} positional argument"
                    f"{'' if len(self.positional) == 1 else 's'} but {len(args)} were given"
                    + (f" (pass {', '.join(self.keyword_only)} by keyword)" if self.keyword_only else ""))
        given = dict(zip(self.positional, args))
        for keyword in kwargs:
            if keyword in given:
                return f"{self.name}() got multiple values for argument '{keyword}'"
        given.update(kwargs)
        for name in self.positional + self.keyword_only:
            if name in self.required and name not in given:
                return f"{self.name}() missing required argument '{name}'"
        for name, value in given.items():
            expected = self.types.get(name)
            if expected == "str" and not isinstance(value, str):
                return f"{self.name}(): {name}: expected a str, got {type(value).__name__}"
            if expected == "os.PathLike" and not isinstance(value, (str, os.PathLike)):
                return f"{self.name}(): {name}: expected a path (a str or os.PathLike), got {type(value).__name__}"
        return None

    def not_unicode(self, args, kwargs):
        """The problem of a str argument (but a path, which may name any file) holding a
        character UTF-8 cannot encode, which no name in a scene holds; None where none
        does."""
        given = dict(zip(self.positional, args)) | kwargs
        for name, value in given.items():
            if self.types.get(name) != "os.PathLike" and _not_unicode(value):
                return f"{self.name}(): {name}: holds a character that is not valid Unicode (a lone surrogate)"
        return None

    def null_in_path(self, args, kwargs):
        """The problem of a path given with a NUL byte, which no file's name holds (Python's
        open() raises ValueError for it); None where there is none."""
        given = dict(zip(self.positional, args)) | kwargs
        for name, value in given.items():
            if self.types.get(name) == "os.PathLike" and isinstance(value, (str, os.PathLike)) and \
                    "\0" in os.fsdecode(value):
                return f"{self.name}(): {name}: embedded null byte"
        return None


def _not_unicode(value):
    """Whether VALUE is a str (or a list or tuple holding one) that UTF-8 cannot encode: one
    with a lone surrogate, as Python decodes bytes it cannot read."""
    if isinstance(value, (list, tuple)):
        return any(_not_unicode(item) for item in value)
    if not isinstance(value, str):
        return False
    try:
        value.encode("utf-8")
    except UnicodeEncodeError:
        return True
    return False


def named_argument_errors(function, name=None):
    """`function` (bound by pybind11) raising one-line TypeErrors for arguments that do not fit,
    which name it as `name` (by default its own name)."""
    signature = _Signature(function.__doc__, name)

    @functools.wraps(function)
    def checked(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except (RuntimeError, UnicodeEncodeError):
            # pybind11 cannot cast such a str to a C++ string, and says so without naming it.
            problem = signature.not_unicode(args[1:] if signature.method else args, kwargs)
            if problem is None:
                raise
            raise ValueError(problem) from None
        except TypeError as error:
            if "incompatible" not in str(error).partition("\n")[0]:
                raise
            own = args[1:] if signature.method else args
            null = signature.null_in_path(own, kwargs)
            if null is not None:
                raise ValueError(null) from None
            problem = signature.problem(own, kwargs)
            if problem is None:
                given = [type(a).__name__ for a in own] + [f"{k}={type(v).__name__}" for k, v in kwargs.items()]
                problem = f"{signature.name}(): arguments of the wrong types ({', '.join(given)}); it takes " \
                          f"({signature.text})"
            raise TypeError(problem) from None
    return checked
