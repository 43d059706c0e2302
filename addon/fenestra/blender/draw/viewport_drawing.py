"""A draw callback in every 3D View, added when the add-on registers and removed when it
unregisters; with `forget`, also called on every depsgraph update (to drop cached geometry)."""

import bpy


class ViewportDrawing:
    def __init__(self, draw, stage, forget=None):
        self.draw, self.stage, self.forget = draw, stage, forget  # stage: 'POST_VIEW' or 'POST_PIXEL'
        self.handle = None

    def register(self):
        if bpy.app.background:  # nothing to draw without a window
            return
        self.handle = bpy.types.SpaceView3D.draw_handler_add(self.draw, (), 'WINDOW', self.stage)
        if self.forget is not None:
            bpy.app.handlers.depsgraph_update_post.append(self.forget)

    def unregister(self):
        if self.handle is not None:
            bpy.types.SpaceView3D.draw_handler_remove(self.handle, 'WINDOW')
            self.handle = None
        if self.forget is not None:
            if self.forget in bpy.app.handlers.depsgraph_update_post:
                bpy.app.handlers.depsgraph_update_post.remove(self.forget)
            self.forget()
