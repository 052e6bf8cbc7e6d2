"""The reserved words of RoboSC (LANGUAGE.md section 1)."""

KEYWORDS = frozenset(
    """robot library component from import behaviour outgoing incoming message action service with
    identifier type request response feedback error cancel links variable on to do goto transition if
    initial marked state string integer none boolean double array value true false datatype object
    enum default and or requirement needs disables provide interface use""".split()
)


def escape_name(name: str) -> str:
    """A name as it must be written: keywords get the ``^`` escape."""
    return f"^{name}" if name in KEYWORDS else name
