"""The error of a scene that cannot be exported as a study: its message says what to change."""


class StudyError(ValueError):
    """A setup that cannot be solved; the message says what to change."""
