"""Errors too long for the status bar, which cuts a message at its width: reported as usual (the
Info editor and scripts keep the whole text) and, in a window, also shown whole in a popup by the
mouse, wrapped to lines that fit."""

import textwrap

import bpy

STATUS_BAR_CHARACTERS = 100  # what the status bar shows of a message, about, in a 1400-pixel window
POPUP_LINE_CHARACTERS = 90


def popup_lines(message):
    """The message's lines in the popup; none when the status bar shows it whole."""
    if len(message) <= STATUS_BAR_CHARACTERS:
        return []
    return textwrap.wrap(message, POPUP_LINE_CHARACTERS)


def report_error(operator, message, title=None):
    """operator.report({'ERROR'}, message), and the popup for a long message in a window."""
    operator.report({'ERROR'}, message)
    lines = popup_lines(message)
    window_manager = bpy.context.window_manager
    if not lines or bpy.app.background or window_manager is None or not window_manager.windows:
        return

    def draw(menu, context):
        for line in lines:
            menu.layout.label(text=line)

    window_manager.popup_menu(draw, title=title or operator.bl_label, icon='ERROR')
