"""The Fenestra menu in the 3D View's Object menu: the study's commands where Blender's menu search
(F3) finds them and where a right-click assigns them a shortcut."""

import bpy


class FENESTRA_MT_study(bpy.types.Menu):
    """Fenestra's commands: solve, evaluate, annual daylight, check the setup"""
    bl_idname = "FENESTRA_MT_study"
    bl_label = "Fenestra"

    def draw(self, context):
        layout = self.layout
        layout.operator("fenestra.solve_openings", icon='MOD_BOOLEAN')
        layout.operator("fenestra.evaluate_openings", icon='PLAY')
        layout.operator("fenestra.annual_daylight", icon='TIME')
        layout.separator()
        layout.operator("fenestra.check_setup", icon='VIEWZOOM')
        layout.operator("fenestra.add_sensor_grid", icon='MESH_GRID')


def draw_in_object_menu(self, context):
    self.layout.separator()
    self.layout.menu(FENESTRA_MT_study.bl_idname)


classes = (FENESTRA_MT_study,)


def register():
    bpy.types.VIEW3D_MT_object.append(draw_in_object_menu)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(draw_in_object_menu)
