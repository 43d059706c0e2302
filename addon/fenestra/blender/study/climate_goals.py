"""Climate goals in the study (export.py's part): the checks before anything is read, the sensor
groups from vertex groups, and the scene file's `goals.climate` / `goals.least_glazing` /
`sensors.groups`. No physics: the native core computes every figure."""

from ..com.study_error import StudyError

ALL = "all"  # the scene file's name for every sensor (not a group name)


def name(goal, index):
    """The goal as the user sees it in the list: "Climate goal 2 (sDA300/50% ≥ 55 %)"."""
    return "Climate goal %d (%s)" % (index + 1, goal.summary())


def group_names(goals):
    """The vertex-group names the climate goals use, in list order, once each."""
    names = []
    for goal in goals.climate:
        group = goal.sensor_group.strip()
        if group and group not in names:
            names.append(group)
    return names


def check_setup(settings):
    """Climate goals need the climate sky, and Climate Goals Only needs climate goals: StudyError
    naming the goal and the fields to change."""
    goals = settings.goals
    climate_sky = settings.sky.type == 'CLIMATE'
    if len(goals.climate) and not climate_sky:
        raise StudyError("%s needs the Climate sky: choose Sky > Climate (weather file), or remove the climate goals "
                     "(Sensors > Climate Goals)" % name(goals.climate[0], 0))
    if goals.source == 'NONE':
        if not climate_sky:
            raise StudyError("No goals: Goals is Climate Goals Only, which needs the Climate sky. Choose Sky > Climate "
                         "(weather file), or Uniform or Painted goals")
        if not len(goals.climate):
            raise StudyError("No goals: Goals is Climate Goals Only and the list of climate goals is empty. Add one "
                         "(Sensors > Climate Goals, +), or choose Uniform or Painted goals")
    for i, goal in enumerate(goals.climate):
        if goal.sensor_group.strip() == ALL:
            raise StudyError("%s: a vertex group cannot be named '%s' (it means every sensor): rename the vertex group, "
                         "or leave Sensor Group empty for all sensors" % (name(goal, i), ALL))
        if goal.metric == 'UDI' and not goal.udi_lower < goal.udi_upper:
            raise StudyError("%s: From (%g lx) must be below To (%g lx)" % (name(goal, i), goal.udi_lower, goal.udi_upper))


def checked_groups(goals, members, sensor_objects):
    """sensors.groups: {vertex-group name: sorted indices of the exported sensors in it}. A group
    that holds no sensor is a StudyError naming the goal, the group and the sensor objects."""
    out = {}
    for i, goal in enumerate(goals.climate):
        group = goal.sensor_group.strip()
        if not group or group in out:
            continue
        if not members.get(group):
            objects = ", ".join("'%s'" % o for o in sensor_objects)
            raise StudyError("%s: Sensor Group '%s' holds no sensor: no vertex of the sensor object%s %s is in a vertex "
                         "group of that name. Assign vertices to it (Object Data > Vertex Groups), or clear Sensor "
                         "Group for all sensors" % (name(goal, i), group, "s" if len(sensor_objects) > 1 else "",
                                                    objects))
        out[group] = sorted(set(members[group]))
    return out


def goals_dict(goals):
    """{"climate": [...], "least_glazing": bool} for the scene file's goals section."""
    return {"climate": [goal.as_dict(goal.sensor_group.strip() or ALL) for goal in goals.climate],
            "least_glazing": bool(goals.least_glazing)}
