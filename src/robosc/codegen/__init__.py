"""Code generation: files made from a network or a supervisor, all from Jinja2 templates
in ``templates/``. :mod:`.cif` writes the network as CIF 3 text."""
