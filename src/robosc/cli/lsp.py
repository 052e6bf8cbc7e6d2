"""``robosc lsp [-I DIR]``: the language server, over standard input and output."""

from __future__ import annotations

import click

from robosc.cli.common import EXIT_OK, exit_with, include_option


@click.command()
@include_option
def lsp(include: tuple[str, ...]) -> None:
    """Run the Language Server Protocol server on standard input and output (for editors:
    live diagnostics, outline, formatting). Libraries are found as by robosc check, and in
    the -I directories and the client's initializationOptions.searchPaths."""
    try:
        from robosc.editor.server import serve
    except ImportError as exc:
        raise click.ClickException(f"robosc lsp needs pygls and lsprotocol: pip install 'robosc[lsp]' ({exc})") from None
    serve(include)
    raise exit_with(EXIT_OK)
