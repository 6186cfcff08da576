"""`python -m lsp` starts the language server on stdio (the same as `logixst lsp`)."""

from .server import run

run()
