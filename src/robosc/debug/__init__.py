"""Seeing what the controller does: the event log, sequence-of-events plots, automaton
diagrams, and the live view in a browser."""
