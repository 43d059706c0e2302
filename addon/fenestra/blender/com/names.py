"""The names the add-on gives to Blender's data, in one place: the attributes it reads and writes on
meshes, the modifiers, collection, objects and nodes it makes (docs/blender.md names them; saved files
and users' scripts rely on them)."""

DOMAIN_ATTRIBUTE = "fenestra_domain"        # face flag: the opening domain (Mark Selected Faces)
GOAL_ATTRIBUTE = "fenestra_goal"            # a sensor mesh's painted goal (colour or float, per vertex or corner)
ACHIEVED_ATTRIBUTE = "fenestra_achieved"    # a sensor mesh's achieved lux (float, per vertex)
ROOM_SIDE_ATTRIBUTE = "fenestra_room_side"  # on a cutter's faces on the room side of the wall
OPENING_RECORD = "fenestra_opening"         # a cutter's custom property: how the solve placed it

BOOLEAN_NAME = "Fenestra Openings"          # the Boolean Difference with the cutters
OPEN_THROUGH_NAME = "Fenestra Open Through"  # the Geometry Nodes modifier after it, and its node group
COLLECTION = "Fenestra Openings"            # the cutters' collection
CUTTER_NAME = "Fenestra Opening %03d"       # each cutter, numbered from 1
SENSORS_NAME = "Fenestra Sensors"           # Add Sensor Grid's mesh and object
WORLD_NODE = "Fenestra Sky"                 # the World's environment texture node with the sky map
