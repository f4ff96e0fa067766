"""What the material operators share: the active material and turning errors into reports."""


def active_material(context):
    obj = context.object
    material = getattr(context, "material", None) or (obj.active_material if obj else None)
    return material


def poll_material(cls, context):
    if active_material(context) is None:
        cls.poll_message_set("No active material")
        return False
    return True
