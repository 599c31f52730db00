"""The command-line reference, generated from fricgen's own argparse parser.

A page writes a heading per command and, under it::

    ```{fricgen-cli} verify
    ```

which renders the command's one-line help, its usage, one entry per argument (flags, metavar or
choices, help text, default) and its examples (the epilog) as the parser has them, so the reference
cannot drift from the code. ``{fricgen-cli}`` without an argument renders the top-level command:
the paragraphs of its description after the first, its usage and its examples. When the build ends, a
subcommand that no page documented is a warning (an error under ``sphinx-build -W``).

The parser is the one the ``fricgen`` command runs: :func:`fricgen.app.cli.commands.parser` (override
with ``fricgen_cli_parser = "module:function"`` in conf.py).
"""

from __future__ import annotations

import argparse
import importlib
import os

from docutils import nodes
from docutils.parsers.rst import directives
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

logger = logging.getLogger(__name__)

WIDTH = "100"  # columns of the rendered usage lines (argparse reads COLUMNS)


#: The function that builds the parser of the ``fricgen`` command (the console script's
#: fricgen.__main__.main runs fricgen.app.cli.commands.main, which parses with it).
DEFAULT_PARSER = "fricgen.app.cli.commands:parser"


def _parser_function(config_value: str | None):
    """The function that builds the parser: ``module:function`` from conf.py, else :data:`DEFAULT_PARSER`."""
    module, _, name = (config_value or DEFAULT_PARSER).partition(":")
    return getattr(importlib.import_module(module), name)


def build_parser(app) -> argparse.ArgumentParser:
    """fricgen's top-level parser (cached on the Sphinx application)."""
    if not hasattr(app, "_fricgen_parser"):
        app._fricgen_parser = _parser_function(app.config.fricgen_cli_parser)()
    return app._fricgen_parser


def subcommands(parser: argparse.ArgumentParser) -> dict[str, tuple[argparse.ArgumentParser, str]]:
    """Each subcommand's name -> (its parser, its one-line help), in the parser's order."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {choice.dest: choice.help or "" for choice in action._choices_actions}
            return {name: (sub, helps.get(name, "")) for name, sub in action.choices.items()}
    return {}


def _usage(parser: argparse.ArgumentParser) -> str:
    before = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = WIDTH
    try:
        return parser.format_usage().removeprefix("usage: ").strip()
    finally:
        if before is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = before


def _signature(action: argparse.Action, formatter: argparse.HelpFormatter) -> str:
    """``--calculus {ito,stratonovich,hk}``, ``--out DIR``, ``LAW ...`` as argparse writes them."""
    if not action.option_strings:
        return formatter._format_args(action, formatter._get_default_metavar_for_positional(action))
    if action.nargs == 0:
        return ", ".join(action.option_strings)
    value = formatter._format_args(action, formatter._get_default_metavar_for_optional(action))
    return ", ".join(f"{flag} {value}" for flag in action.option_strings)


def _meaning(action: argparse.Action, formatter: argparse.HelpFormatter) -> str:
    text = formatter._expand_help(action) if action.help else ""
    notes = []
    if action.required and action.nargs not in ("*", "?"):  # argparse marks a "*" positional required too
        notes.append("required")
    shown = action.default not in (None, False, [], argparse.SUPPRESS) and action.nargs != 0
    if shown and "default" not in text:
        notes.append(f"default: {action.default}")
    if notes:
        text = f"{text} ({'; '.join(notes)})" if text else "; ".join(notes).capitalize()
    return text


def _paragraph(text: str) -> nodes.paragraph:
    """A paragraph of help text, its ``literal`` spans (reST markup in docstrings) as code."""
    paragraph = nodes.paragraph()
    for i, part in enumerate(text.split("``")):
        if part:
            paragraph += nodes.literal(text=part) if i % 2 else nodes.Text(part)
    return paragraph


def argument_list(parser: argparse.ArgumentParser) -> nodes.definition_list:
    """One definition-list item per argument (``--help`` left out)."""
    formatter = parser._get_formatter()
    items = nodes.definition_list(classes=["fricgen-cli-arguments"])
    for action in parser._actions:
        if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
            continue
        term = nodes.term()
        term += nodes.literal(text=_signature(action, formatter))
        definition = nodes.definition()
        definition += _paragraph(_meaning(action, formatter))
        items += nodes.definition_list_item("", term, definition)
    return items


def _examples(parser: argparse.ArgumentParser) -> list[nodes.Node]:
    """The parser's epilog ("examples:" and command lines) as a paragraph and a shell block."""
    if not parser.epilog:
        return []
    title, _, lines = parser.epilog.partition("\n")
    return [nodes.paragraph(text=title.rstrip(":").capitalize() + ":"), nodes.literal_block(text=lines, language="bash")]


class FricgenCli(SphinxDirective):
    """``{fricgen-cli} [COMMAND]``: help, usage and arguments of ``fricgen COMMAND`` (or of ``fricgen``)."""

    optional_arguments = 1
    option_spec = {"no-arguments": directives.flag}

    def run(self) -> list[nodes.Node]:
        parser = build_parser(self.env.app)
        commands = subcommands(parser)
        if not self.arguments:
            result = [_paragraph(" ".join(part.split())) for part in (parser.description or "").split("\n\n")[1:]]
            result.append(nodes.literal_block(text=_usage(parser), language="text"))
            return result + _examples(parser)
        name = self.arguments[0]
        if name not in commands:
            raise self.error(f"fricgen has no command {name!r} (it has: {', '.join(commands)})")
        self.env.fricgen_cli_documented = getattr(self.env, "fricgen_cli_documented", {})
        self.env.fricgen_cli_documented[name] = self.env.docname
        sub, help_line = commands[name]
        result = [_paragraph(help_line)] if help_line else []
        result.append(nodes.literal_block(text=_usage(sub), language="text"))
        if "no-arguments" not in self.options:
            result.append(argument_list(sub))
        return result + _examples(sub)


def _merge(app, env, docnames, other) -> None:
    env.fricgen_cli_documented = {**getattr(env, "fricgen_cli_documented", {}), **getattr(other, "fricgen_cli_documented", {})}


def _purge(app, env, docname) -> None:
    documented = getattr(env, "fricgen_cli_documented", {})
    for name in [n for n, page in documented.items() if page == docname]:
        del documented[name]


def _check_all_documented(app, env) -> None:
    documented = getattr(env, "fricgen_cli_documented", {})
    missing = [name for name in subcommands(build_parser(app)) if name not in documented]
    if missing:
        logger.warning("fricgen commands without a {fricgen-cli} entry in the docs: %s", ", ".join(missing))


def setup(app):
    app.add_config_value("fricgen_cli_parser", None, "env")
    app.add_directive("fricgen-cli", FricgenCli)
    app.connect("env-purge-doc", _purge)
    app.connect("env-merge-info", _merge)
    app.connect("env-check-consistency", _check_all_documented)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
