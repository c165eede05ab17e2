from setuptools import find_packages, setup

package_name = 'ros2cli'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='The ros2 command line tool, compatible with upstream ros2cli.',
    license='Apache-2.0',
    tests_require=['pytest'],
    # `ros2` goes to <prefix>/bin, which the workspace setup puts on PATH.
    # Commands and verbs are found through these groups (ros2cli.entry_points); other packages
    # add theirs the same way. Group names are upstream's.
    entry_points={
        'console_scripts': [
            'ros2 = ros2cli.cli:console_main',
        ],
        'ros2cli.command': [
            'action = ros2cli.command.action:ActionCommand',
            'daemon = ros2cli.command.daemon:DaemonCommand',
            'extension_points = ros2cli.command.extension_points:ExtensionPointsCommand',
            'extensions = ros2cli.command.extensions:ExtensionsCommand',
            'interface = ros2cli.command.interface:InterfaceCommand',
            'node = ros2cli.command.node:NodeCommand',
            'param = ros2cli.command.param:ParamCommand',
            'run = ros2cli.command.run:RunCommand',
            'service = ros2cli.command.service:ServiceCommand',
            'topic = ros2cli.command.topic:TopicCommand',
        ],
        'ros2cli.extension_point': [
            'ros2cli.command = ros2cli.command:CommandExtension',
            'ros2action.verb = ros2cli.verb:VerbExtension',
            'ros2cli.daemon.verb = ros2cli.verb:VerbExtension',
            'ros2interface.verb = ros2cli.verb:VerbExtension',
            'ros2node.verb = ros2cli.verb:VerbExtension',
            'ros2param.verb = ros2cli.verb:VerbExtension',
            'ros2service.verb = ros2cli.verb:VerbExtension',
            'ros2topic.verb = ros2cli.verb:VerbExtension',
        ],
        'ros2action.verb': [
            'info = ros2cli.verb.action.info:InfoVerb',
            'list = ros2cli.verb.action.list:ListVerb',
            'send_goal = ros2cli.verb.action.send_goal:SendGoalVerb',
            'type = ros2cli.verb.action.type:TypeVerb',
        ],
        'ros2cli.daemon.verb': [
            'start = ros2cli.verb.daemon.start:StartVerb',
            'status = ros2cli.verb.daemon.status:StatusVerb',
            'stop = ros2cli.verb.daemon.stop:StopVerb',
        ],
        'ros2interface.verb': [
            'list = ros2cli.verb.interface.list:ListVerb',
            'package = ros2cli.verb.interface.package:PackageVerb',
            'packages = ros2cli.verb.interface.packages:PackagesVerb',
            'proto = ros2cli.verb.interface.proto:ProtoVerb',
            'show = ros2cli.verb.interface.show:ShowVerb',
        ],
        'ros2node.verb': [
            'info = ros2cli.verb.node.info:InfoVerb',
            'list = ros2cli.verb.node.list:ListVerb',
        ],
        'ros2param.verb': [
            'delete = ros2cli.verb.param.delete:DeleteVerb',
            'describe = ros2cli.verb.param.describe:DescribeVerb',
            'dump = ros2cli.verb.param.dump:DumpVerb',
            'get = ros2cli.verb.param.get:GetVerb',
            'list = ros2cli.verb.param.list:ListVerb',
            'load = ros2cli.verb.param.load:LoadVerb',
            'set = ros2cli.verb.param.set:SetVerb',
        ],
        'ros2service.verb': [
            'call = ros2cli.verb.service.call:CallVerb',
            'echo = ros2cli.verb.service.echo:EchoVerb',
            'find = ros2cli.verb.service.find:FindVerb',
            'info = ros2cli.verb.service.info:InfoVerb',
            'list = ros2cli.verb.service.list:ListVerb',
            'type = ros2cli.verb.service.type:TypeVerb',
        ],
        'ros2topic.verb': [
            'bw = ros2cli.verb.topic.bw:BwVerb',
            'echo = ros2cli.verb.topic.echo:EchoVerb',
            'find = ros2cli.verb.topic.find:FindVerb',
            'hz = ros2cli.verb.topic.hz:HzVerb',
            'info = ros2cli.verb.topic.info:InfoVerb',
            'list = ros2cli.verb.topic.list:ListVerb',
            'pub = ros2cli.verb.topic.pub:PubVerb',
            'type = ros2cli.verb.topic.type:TypeVerb',
        ],
    },
)
