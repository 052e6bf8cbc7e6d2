"""Editor support: ``robosc lsp``, a Language Server Protocol server over the language stage."""
