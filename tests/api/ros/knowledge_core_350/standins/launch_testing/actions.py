"""``launch_testing.actions.ReadyToTest``: inert."""


class ReadyToTest:
    pass
