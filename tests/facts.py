"""What a message must name, not its sentence.

A message is tested for the facts it must name (the option or argument,
the value given, the place, what is allowed), each as it is written, in
any order and with any words around them (STYLE.md, Tests): the wording
can improve freely, and a message that drops a fact fails.
"""


def names(message, *facts):
    """Assert that ``message`` (a string or an exception) names every one
    of ``facts``; returns the message as a string."""
    text = str(message)
    missing = [fact for fact in facts if str(fact) not in text]
    assert not missing, f"the message does not name {missing}: {text!r}"
    return text


def names_none(message, *facts):
    """Assert that ``message`` names none of ``facts`` (what it must not
    say: a traceback, a wrong option)."""
    text = str(message)
    found = [fact for fact in facts if str(fact) in text]
    assert not found, f"the message names {found}: {text!r}"
    return text
