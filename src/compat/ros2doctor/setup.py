from setuptools import find_packages, setup

package_name = 'ros2doctor'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml', 'README.md']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='ros2 doctor: checks and reports of this ROS 2 setup.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'ros2cli.command': [
            'doctor = ros2doctor.command.doctor:DoctorCommand',
            'wtf = ros2doctor.command.doctor:WtfCommand',
        ],
        'ros2doctor.checks': [
            'NetworkCheck = ros2doctor.api.network:NetworkCheck',
            'PackageCheck = ros2doctor.api.package:PackageCheck',
            'PlatformCheck = ros2doctor.api.platform:PlatformCheck',
            'QoSCompatibilityCheck = ros2doctor.api.topic:QoSCompatibilityCheck',
            'TopicCheck = ros2doctor.api.topic:TopicCheck',
        ],
        'ros2doctor.report': [
            'NetworkReport = ros2doctor.api.network:NetworkReport',
            'PackageReport = ros2doctor.api.package:PackageReport',
            'PlatformReport = ros2doctor.api.platform:PlatformReport',
            'QoSCompatibilityReport = ros2doctor.api.topic:QoSCompatibilityReport',
            'RMWReport = ros2doctor.api.rmw:RMWReport',
            'RosdistroReport = ros2doctor.api.platform:RosdistroReport',
            'TopicReport = ros2doctor.api.topic:TopicReport',
        ],
        'ros2cli.extension_point': ['ros2doctor.verb = ros2doctor.verb:VerbExtension'],
        'ros2doctor.verb': ['hello = ros2doctor.verb.hello:HelloVerb'],
    },
)
