"""The app tests' check: expect(condition, context...) raises AssertionError with the context
when the condition is false. Unlike an assert statement it is not removed by python3 -O (or
PYTHONOPTIMIZE), so a test cannot pass by having its checks compiled away. A context item that is
callable is called only on failure (for context that exists only then)."""


def expect(condition, *context):
    if not condition:
        raise AssertionError(*(c() if callable(c) else c for c in context))
