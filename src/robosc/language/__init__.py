"""The language stage: text in, checked model out.

Passes, in order (each in its own module):

1. :mod:`.parser` -- text to syntax nodes (:mod:`.syntax`), syntax errors as diagnostics;
2. :mod:`.loader` -- finds and parses the libraries a robot imports;
3. :mod:`.resolver` -- syntax nodes to the checked model (:mod:`.model`), every
   reference resolved to the object it names, expression types computed (:mod:`.types`);
4. :mod:`.checks` -- the static rules of LANGUAGE.md section 5, one module each.
"""
