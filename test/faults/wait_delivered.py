#!/usr/bin/env python3
"""Waits until a subscriber node has received every message a publisher node has sent it: for every topic the
subscriber takes from the publisher, the messages the publisher queued for its subscribers (roscpp's bus
statistics count a message when it is queued) equal those the subscriber's transport received. Meant for a
publisher that has stopped publishing and one subscriber per topic (a paused sim_node and rosbag record).
  wait_delivered.py PUBLISHER SUBSCRIBER TIMEOUT   exit 0 once delivered, 1 with the counts at the deadline"""
import sys
import time
import xmlrpc.client
from typing import Any, Dict, List, Tuple

import rosgraph


def bus_stats(master: rosgraph.Master, node: str) -> Tuple[List[Any], List[Any]]:
    """roscpp's getBusStats: (publications, subscriptions); roscpp answers with them alone, not in the
    (code, status, value) triple of the other calls."""
    answer: Any = xmlrpc.client.ServerProxy(master.lookupNode(node)).getBusStats("/wait_delivered")
    stats = answer[2] if len(answer) == 3 and isinstance(answer[0], int) else answer
    return stats[0], stats[1]


def counts(master: rosgraph.Master, publisher: str, subscriber: str) -> Dict[str, Tuple[int, int]]:
    """Per topic the subscriber takes: (queued by the publisher for all its links, received by the subscriber).
    A publication's link is [id, bytes, data bytes, messages, connected]; a subscription's [id, bytes,
    messages, drops, connected]."""
    publications, _ = bus_stats(master, publisher)
    _, subscriptions = bus_stats(master, subscriber)
    sent = {topic: sum(link[3] for link in links) for topic, links in publications}
    return {topic: (sent[topic], sum(link[2] for link in links))
            for topic, links in subscriptions if topic in sent}


def main() -> int:
    publisher, subscriber, timeout = sys.argv[1], sys.argv[2], float(sys.argv[3])
    master = rosgraph.Master("/wait_delivered")
    deadline = time.monotonic() + timeout
    while True:
        now = counts(master, publisher, subscriber)
        if now and all(sent == received for sent, received in now.values()):
            print(f"wait_delivered: {subscriber} has every message {publisher} sent it on {len(now)} topics")
            return 0
        if time.monotonic() > deadline:
            late = {topic: c for topic, c in now.items() if c[0] != c[1]}
            print(f"wait_delivered: after {timeout:g} s, (sent, received) differ: {late}", file=sys.stderr)
            return 1
        time.sleep(0.1)  # the period of the look


if __name__ == "__main__":
    sys.exit(main())
