"""The type stubs (_rangefill.pyi) name every function and give the defaults it has at run time."""

import ast
import pathlib
import re

import rangefill


def runtime_defaults(function):
    """{parameter: default} from the signature pybind11 puts on the docstring's first line."""
    signature = function.__doc__.splitlines()[0]
    return {name: ast.literal_eval(value)
            for name, value in re.findall(r"(\w+): [\w.\[\]]+ = ('[^']*'|[^,)]+)", signature)}


def test_the_stubs_match_the_module():
    stub = pathlib.Path(rangefill.__file__).with_name("_rangefill.pyi").read_text()
    functions = {node.name: node for node in ast.parse(stub).body
                 if isinstance(node, ast.FunctionDef)}
    assert set(functions) == set(rangefill.__all__) - {"Mesh", "ProcessingError"}
    for name, node in functions.items():
        arguments = node.args
        stub_defaults = {}
        positional = arguments.args[len(arguments.args) - len(arguments.defaults):]
        for argument, default in [*zip(positional, arguments.defaults),
                                  *zip(arguments.kwonlyargs, arguments.kw_defaults)]:
            if default is not None:
                stub_defaults[argument.arg] = eval(ast.unparse(default))  # literals and 1 / 64
        runtime = runtime_defaults(getattr(rangefill, name))
        for argument in [a for a, value in stub_defaults.items() if value is Ellipsis]:
            assert isinstance(runtime[argument], int), (name, argument)  # the machine's
            stub_defaults[argument] = runtime[argument]
        assert stub_defaults == runtime, name
