"""Errors too long for the status bar, which cuts a message at its width. In a window Blender shows
an operator's error in a popup by the mouse too, one label per line of the message: a long one is
reported wrapped to lines that fit, so that the popup shows it whole. Scripts and background runs
get the message on one line, as the core words it."""

import textwrap

import bpy

STATUS_BAR_CHARACTERS = 100  # what the status bar shows of a message, about, in a 1400-pixel window
POPUP_LINE_CHARACTERS = 90


def popup_lines(message):
    """The message's lines in the popup; none when the status bar shows it whole."""
    if len(message) <= STATUS_BAR_CHARACTERS:
        return []
    return textwrap.wrap(message, POPUP_LINE_CHARACTERS)


def report_error(operator, message):
    """operator.report({'ERROR'}, message), wrapped for Blender's popup when long, in a window."""
    lines = popup_lines(message)
    if lines and not bpy.app.background:
        message = "\n".join(lines)
    operator.report({'ERROR'}, message)
