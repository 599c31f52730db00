"""The engine's thread count: measured, the faster kept, the slower measured again less and less often."""

from fricgen.langevin.threads import CHUNK_SECONDS, PROBE_EVERY, PROBE_MOST, ThreadChoice


def run(choice: ThreadChoice, rates: dict[int, float], chunks: int) -> list[int]:
    """Thread counts of ``chunks`` chunks when ``threads`` threads run at ``rates[threads]`` steps/s."""
    used = []
    for _ in range(chunks):
        threads = choice.next()
        steps = choice.steps(threads, 10**9)
        choice.record(threads, steps, steps / rates[threads])
        used.append(threads)
    return used


def test_the_faster_count_is_kept_and_the_slower_probed_ever_more_rarely():
    choice = ThreadChoice(2)
    used = run(choice, {1: 100.0, 2: 30.0}, 300)  # two threads slower: a busy machine
    assert used[:2] == [1, 2] and used.count(2) < 12
    assert choice.interval == PROBE_MOST
    gaps = [b - a for a, b in zip([i for i, n in enumerate(used) if n == 2], [i for i, n in enumerate(used) if n == 2][1:])]
    assert gaps == sorted(gaps) and gaps[0] == PROBE_EVERY + 1


def test_a_count_that_became_faster_takes_over():
    choice = ThreadChoice(2)
    run(choice, {1: 100.0, 2: 30.0}, 40)
    used = run(choice, {1: 100.0, 2: 300.0}, 200)  # the competitor has gone
    assert used[-20:].count(2) >= 19


def test_one_thread_only_and_chunks_of_chunk_seconds():
    choice = ThreadChoice(1)
    assert run(choice, {1: 1000.0}, 5) == [1] * 5
    assert choice.steps(1, 10**9) == round(1000.0 * CHUNK_SECONDS) and choice.steps(1, 7) == 7
