"""owl network's verdicts from facts: the good set-up and each broken one, with its fix."""

from owl_cli.network.checks import FACTORY_ADDRESS, Interface, NetworkFacts, verdict

ON_SUBNET = [Interface('lo', '127.0.0.1', 8), Interface('enx0', '10.42.0.1', 24)]
ALL_ANSWER = {'10.42.0.20': True, '10.42.0.8': True, '10.42.0.9': True, '10.42.0.10': True,
              FACTORY_ADDRESS: False}
NODES = ['olive_imu_x1_dcm_srv', 'olive_servo_pan_dcm_srv']


def facts(**changes) -> NetworkFacts:
    values = dict(discovery_range='SUBNET', domain_id=0, interfaces=ON_SUBNET, answering=ALL_ANSWER,
                  olive_nodes=NODES)
    values.update(changes)
    return NetworkFacts(**values)


def problems(f: NetworkFacts) -> list[str]:
    return [v.text for v in verdict(f) if not v.ok]


def test_a_good_set_up_has_no_problem():
    assert problems(facts()) == []
    texts = [str(v) for v in verdict(facts())]
    assert texts[1] == "ok: enx0 10.42.0.1/24 is on the modules' subnet 10.42.0.0/24"
    assert 'servo pan at 10.42.0.8' in texts[2]


def test_private_mode_says_how_to_open_it():
    [problem] = problems(facts(discovery_range='LOCALHOST', olive_nodes=[]))
    assert problem.endswith('fix: export OWL_NETWORK=open; source env.sh')


def test_no_interface_on_the_subnet_names_what_the_machine_has():
    [problem, *_] = problems(facts(interfaces=[Interface('eth0', '192.168.1.4', 24)],
                                   answering=dict.fromkeys(ALL_ANSWER, False), olive_nodes=[]))
    assert ("no network interface on the modules' subnet 10.42.0.0/24 "
            '(this machine has: eth0 192.168.1.4/24)') in problem


def test_no_module_answering_points_at_cables_and_bridge():
    [problem] = problems(facts(answering=dict.fromkeys(ALL_ANSWER, False), olive_nodes=[]))
    assert problem.startswith('no Olive module answers on 10.42.0.0/24')


def test_a_domain_mismatch_says_which_domain():
    [problem] = problems(facts(domain_id=7, olive_nodes=[], olive_nodes_in_domain_0=NODES))
    assert problem.endswith('this shell is in domain 7; fix: export ROS_DOMAIN_ID=0')


def test_modules_answering_without_dds_suggest_a_firewall():
    [problem] = problems(facts(olive_nodes=[]))
    assert 'a firewall may block DDS (UDP 7400-7700)' in problem
    assert 'enx0' in problem


def test_a_module_at_the_factory_address_is_told_to_move():
    [problem] = problems(facts(answering={**ALL_ANSWER, FACTORY_ADDRESS: True}))
    assert problem.startswith('a module answers at 10.42.0.7, the factory address')


def test_the_graph_partition_is_reported_and_its_absence_is_a_problem_with_a_fix():
    [last] = [v for v in verdict(facts(graph_profile='/x/config/fastdds.xml'))][-1:]
    assert last.ok
    assert 'Humble modules are safe beside this shell: /x/config/fastdds.xml' in last.text
    [problem] = problems(facts(graph_profile='/home/me/mine.xml', graph_protected=False))
    assert '(/home/me/mine.xml) does not keep our graph messages from Humble modules' in problem
    assert 'fix: unset FASTRTPS_DEFAULT_PROFILES_FILE; source env.sh' in problem


def test_each_node_is_named_with_its_distribution_when_known():
    texts = [v.text for v in verdict(facts(distributions={NODES[0]: 'ROS 2 Humble'}))]
    assert f'{NODES[0]} (ROS 2 Humble), {NODES[1]}' in texts[3]
